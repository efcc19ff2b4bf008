//! Point tables: PLY (ascii or binary little-endian, through `ply-rs-bw`) and CSV (through `csv`).
//!
//! A [`PointTable`] is the `vertex` element of a PLY file (or the rows of a CSV file): named
//! numeric columns, one row per point. Columns are floats, except integer ones (such as
//! `element`), which keep their integer type when written.

use std::io::BufWriter;
use std::path::Path;

use ply_rs_bw::ply::{
    Addable, DefaultElement, ElementDef, Encoding, Ply, Property, PropertyDef, PropertyType, ScalarType,
};

use crate::{IoError, Result, write_with};

/// How a column is stored.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ColumnKind {
    /// A floating-point value (`float` in PLY).
    Float,
    /// An integer value (`int` in PLY), such as an element id or a label.
    Int,
}

/// A named column.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Column {
    /// Property name (`x`, `y`, `z`, `element`, `red`...).
    pub name: String,
    /// Storage kind.
    pub kind: ColumnKind,
}

/// Points as rows of named numeric columns.
#[derive(Debug, Clone, PartialEq)]
pub struct PointTable {
    /// The columns, in file order.
    pub columns: Vec<Column>,
    /// Number of points.
    pub rows: usize,
    /// Row-major values: point `i`, column `j` is `values[i * columns.len() + j]`.
    pub values: Vec<f64>,
}

impl PointTable {
    /// Index of the column named `name`.
    pub fn column(&self, name: &str) -> Option<usize> {
        self.columns.iter().position(|column| column.name == name)
    }

    /// The values of row `row`.
    pub fn row(&self, row: usize) -> &[f64] {
        let width = self.columns.len();
        &self.values[row * width..(row + 1) * width]
    }
}

/// File format for points.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PointFormat {
    /// PLY, ascii.
    PlyAscii,
    /// PLY, binary little-endian.
    PlyBinary,
    /// Comma-separated values with a header row of column names.
    Csv,
}

impl PointFormat {
    /// The format suggested by a file name: `.csv` is CSV, anything else PLY (binary).
    pub fn from_path(path: &Path) -> PointFormat {
        match path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
            Some("csv") => PointFormat::Csv,
            _ => PointFormat::PlyBinary,
        }
    }
}

/// Reads points from PLY (any encoding; the `vertex` element, scalar properties) or CSV (chosen
/// by the `.csv` extension). Fails when there are no points or a value is not a number.
pub fn read_points(path: &Path) -> Result<PointTable> {
    parse_points(&crate::read_bytes(path)?, PointFormat::from_path(path), path)
}

/// Parses the bytes of a point file as [`read_points`] does: CSV for [`PointFormat::Csv`], PLY
/// (any encoding) otherwise; `path` is the file (or label) errors name.
pub fn parse_points(bytes: &[u8], format: PointFormat, path: &Path) -> Result<PointTable> {
    let table = if format == PointFormat::Csv { parse_csv(bytes, path)? } else { parse_ply(bytes, path)? };
    if table.rows == 0 {
        return Err(IoError::format(path, "holds no points"));
    }
    Ok(table)
}

fn parse_ply(bytes: &[u8], path: &Path) -> Result<PointTable> {
    let parser = ply_rs_bw::parser::Parser::<DefaultElement>::new();
    let ply = parser
        .read_ply(&mut std::io::Cursor::new(bytes))
        .map_err(|error| IoError::format(path, format!("is not a valid PLY file: {error}")))?;
    let element = ply.header.elements.get("vertex").ok_or_else(|| {
        IoError::format(path, "PLY has no `vertex` element (points are read from `element vertex N`)")
    })?;
    let mut columns = Vec::new();
    for (name, definition) in &element.properties {
        match &definition.data_type {
            PropertyType::Scalar(ScalarType::Float | ScalarType::Double) => {
                columns.push(Column { name: name.clone(), kind: ColumnKind::Float })
            }
            PropertyType::Scalar(_) => columns.push(Column { name: name.clone(), kind: ColumnKind::Int }),
            PropertyType::List(..) => {}
        }
    }
    let vertices = ply.payload.get("vertex").map(Vec::as_slice).unwrap_or(&[]);
    let mut values = Vec::with_capacity(vertices.len() * columns.len());
    for vertex in vertices {
        for column in &columns {
            let value = match vertex.get(&column.name) {
                Some(Property::Char(v)) => f64::from(*v),
                Some(Property::UChar(v)) => f64::from(*v),
                Some(Property::Short(v)) => f64::from(*v),
                Some(Property::UShort(v)) => f64::from(*v),
                Some(Property::Int(v)) => f64::from(*v),
                Some(Property::UInt(v)) => f64::from(*v),
                Some(Property::Float(v)) => f64::from(*v),
                Some(Property::Double(v)) => *v,
                _ => return Err(IoError::format(path, format!("vertex property `{}` is missing", column.name))),
            };
            values.push(value);
        }
    }
    Ok(PointTable { columns, rows: vertices.len(), values })
}

fn parse_csv(bytes: &[u8], path: &Path) -> Result<PointTable> {
    let mut reader = csv::ReaderBuilder::new().trim(csv::Trim::All).from_reader(bytes);
    let headers =
        reader.headers().map_err(|error| IoError::format(path, format!("invalid CSV header: {error}")))?.clone();
    let mut columns: Vec<Column> =
        headers.iter().map(|name| Column { name: name.to_string(), kind: ColumnKind::Int }).collect();
    let mut values = Vec::new();
    let mut rows = 0;
    for (line, record) in reader.records().enumerate() {
        let record = record.map_err(|error| IoError::format(path, format!("invalid CSV: {error}")))?;
        if record.len() != columns.len() {
            return Err(IoError::format(
                path,
                format!("row {} has {} values, expected {}", line + 2, record.len(), columns.len()),
            ));
        }
        for (column, field) in columns.iter_mut().zip(record.iter()) {
            let value: f64 = field.parse().map_err(|_| {
                IoError::format(path, format!("row {}, column `{}`: `{field}` is not a number", line + 2, column.name))
            })?;
            if field.contains(['.', 'e', 'E']) || value.fract() != 0.0 {
                column.kind = ColumnKind::Float;
            }
            values.push(value);
        }
        rows += 1;
    }
    for column in &mut columns {
        if column.name != "element" && column.name != "label" {
            column.kind = ColumnKind::Float;
        }
    }
    Ok(PointTable { columns, rows, values })
}

/// Writes points atomically in `format`. Float columns are written as PLY `float` (32-bit), int
/// columns as `int`.
pub fn write_points(path: &Path, table: &PointTable, format: PointFormat) -> Result<()> {
    if table.values.len() != table.rows * table.columns.len() {
        return Err(IoError::format(path, "point table values do not match rows × columns"));
    }
    match format {
        PointFormat::Csv => write_csv(path, table),
        PointFormat::PlyAscii => write_ply(path, table, Encoding::Ascii),
        PointFormat::PlyBinary => write_ply(path, table, Encoding::BinaryLittleEndian),
    }
}

fn write_ply(path: &Path, table: &PointTable, encoding: Encoding) -> Result<()> {
    let mut ply = Ply::<DefaultElement>::new();
    ply.header.encoding = encoding;
    ply.header.comments.push("written by motif".to_string());
    let mut element = ElementDef::new("vertex".to_string());
    for column in &table.columns {
        let scalar = match column.kind {
            ColumnKind::Float => ScalarType::Float,
            ColumnKind::Int => ScalarType::Int,
        };
        element.properties.add(PropertyDef::new(column.name.clone(), PropertyType::Scalar(scalar)));
    }
    ply.header.elements.add(element);
    let vertices = (0..table.rows)
        .map(|row| {
            let mut vertex = DefaultElement::new();
            for (column, &value) in table.columns.iter().zip(table.row(row)) {
                let property = match column.kind {
                    ColumnKind::Float => Property::Float(value as f32),
                    ColumnKind::Int => Property::Int(value.round() as i32),
                };
                vertex.insert(column.name.clone(), property);
            }
            vertex
        })
        .collect();
    ply.payload.insert("vertex".to_string(), vertices);
    write_with(path, |file| {
        let mut out = BufWriter::new(file);
        ply_rs_bw::writer::Writer::new().write_ply(&mut out, &mut ply).map(|_| ())?;
        std::io::Write::flush(&mut out)
    })
}

fn write_csv(path: &Path, table: &PointTable) -> Result<()> {
    write_with(path, |file| {
        let mut writer = csv::Writer::from_writer(BufWriter::new(file));
        writer.write_record(table.columns.iter().map(|column| column.name.as_str()))?;
        for row in 0..table.rows {
            let fields: Vec<String> = table
                .columns
                .iter()
                .zip(table.row(row))
                .map(|(column, value)| match column.kind {
                    ColumnKind::Float => format!("{value}"),
                    ColumnKind::Int => format!("{}", value.round() as i64),
                })
                .collect();
            writer.write_record(&fields)?;
        }
        writer.flush()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> PointTable {
        PointTable {
            columns: vec![
                Column { name: "x".into(), kind: ColumnKind::Float },
                Column { name: "y".into(), kind: ColumnKind::Float },
                Column { name: "element".into(), kind: ColumnKind::Int },
                Column { name: "radius".into(), kind: ColumnKind::Float },
            ],
            rows: 3,
            values: vec![0.5, 1.25, 0.0, 0.1, -2.0, 3.0, 1.0, 0.2, 4.0, 5.5, 1.0, 0.3],
        }
    }

    fn assert_close(a: &PointTable, b: &PointTable) {
        assert_eq!(a.columns, b.columns);
        assert_eq!(a.rows, b.rows);
        for (x, y) in a.values.iter().zip(&b.values) {
            assert!((x - y).abs() < 1e-6, "{x} vs {y}");
        }
    }

    #[test]
    fn ply_and_csv_round_trips() {
        let dir = tempfile::tempdir().unwrap();
        for (name, format) in
            [("a.ply", PointFormat::PlyAscii), ("b.ply", PointFormat::PlyBinary), ("c.csv", PointFormat::Csv)]
        {
            let path = dir.path().join(name);
            write_points(&path, &sample(), format).unwrap();
            assert_close(&read_points(&path).unwrap(), &sample());
        }
        let text = std::fs::read_to_string(dir.path().join("a.ply")).unwrap();
        assert!(text.starts_with("ply\nformat ascii 1.0"), "{text}");
        assert!(text.contains("property int element"));
    }

    #[test]
    fn bad_point_files_give_errors_naming_the_file() {
        let dir = tempfile::tempdir().unwrap();
        let wrong_header = dir.path().join("wrong.ply");
        std::fs::write(&wrong_header, "ply\nformat ascii 1.0\nelement vertex 2\nproperty float\nend_header\n1\n2\n")
            .unwrap();
        let message = read_points(&wrong_header).unwrap_err().to_string();
        assert!(message.contains("wrong.ply"), "{message}");
        let not_ply = dir.path().join("text.ply");
        std::fs::write(&not_ply, "hello").unwrap();
        assert!(read_points(&not_ply).unwrap_err().to_string().contains("text.ply"));
        let faces_only = dir.path().join("faces.ply");
        std::fs::write(
            &faces_only,
            "ply\nformat ascii 1.0\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n",
        )
        .unwrap();
        assert!(read_points(&faces_only).unwrap_err().to_string().contains("vertex"));
        let bad_csv = dir.path().join("bad.csv");
        std::fs::write(&bad_csv, "x,y\n1,2\n3,abc\n").unwrap();
        let message = read_points(&bad_csv).unwrap_err().to_string();
        assert!(message.contains("bad.csv") && message.contains("abc"), "{message}");
        assert!(read_points(&dir.path().join("missing.ply")).unwrap_err().to_string().contains("missing.ply"));
    }
}
