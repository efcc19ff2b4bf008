//! Point sets as named columns, the shape every front end holds them in (a PLY or CSV table in
//! the CLI, a dict of numpy arrays in Python): `x`, `y` (and `z` in 3D) are positions, `element`
//! groups points into rigid elements, every other column is an attribute; integer columns are
//! attributes that stay discrete.

use motif_core::InvalidParameter;
use motif_points::PointSet;

use crate::JobError;

/// One named column of a point set.
#[derive(Debug, Clone, PartialEq)]
pub struct Column {
    /// The name (`x`, `y`, `z`, `element` or an attribute).
    pub name: String,
    /// True for whole-number columns (labels, ids): such attributes are kept discrete.
    pub integer: bool,
    /// One value per point.
    pub values: Vec<f64>,
}

/// The point set the columns describe, and the names of its discrete (integer) attributes.
/// `what` names the set in errors (`exemplar`, `existing points`).
pub fn point_set(columns: &[Column], what: &str) -> Result<(PointSet, Vec<String>), JobError> {
    let find = |name: &str| columns.iter().position(|c| c.name == name);
    let (Some(x), Some(y)) = (find("x"), find("y")) else {
        let names: Vec<&str> = columns.iter().map(|c| c.name.as_str()).collect();
        let value = format!("columns {}", names.join(", "));
        return Err(InvalidParameter::new(what, value, "points need x and y columns (and optionally z)").into());
    };
    let rows = columns[x].values.len();
    if let Some(column) = columns.iter().find(|c| c.values.len() != rows) {
        let value = format!("column `{}` of {} values", column.name, column.values.len());
        return Err(
            InvalidParameter::new(what, value, format!("every column must hold {rows} values, as x does")).into()
        );
    }
    let z = find("z");
    let element = find("element");
    let dimension = if z.is_some() { 3 } else { 2 };
    let attribute_columns: Vec<usize> =
        (0..columns.len()).filter(|&c| Some(c) != z && c != x && c != y && Some(c) != element).collect();
    let mut positions = Vec::with_capacity(rows * dimension);
    let mut attributes = Vec::with_capacity(rows * attribute_columns.len());
    let mut elements = Vec::new();
    for row in 0..rows {
        positions.push(columns[x].values[row]);
        positions.push(columns[y].values[row]);
        if let Some(z) = z {
            positions.push(columns[z].values[row]);
        }
        for &c in &attribute_columns {
            attributes.push(columns[c].values[row]);
        }
        if let Some(e) = element {
            let id = columns[e].values[row];
            if !(id.is_finite() && id.fract() == 0.0 && id.abs() < 1e15) {
                let value = format!("element {id} on row {}", row + 1);
                let allowed = "element ids are whole numbers (points sharing one form a rigid element; -1 for none)";
                return Err(InvalidParameter::new(what, value, allowed).into());
            }
            elements.push(id as i64);
        }
    }
    let discrete =
        attribute_columns.iter().filter(|&&c| columns[c].integer).map(|&c| columns[c].name.clone()).collect();
    let set = PointSet {
        dimension,
        positions,
        attribute_names: attribute_columns.iter().map(|&c| columns[c].name.clone()).collect(),
        attributes,
        elements: element.map(|_| elements),
    };
    Ok((set, discrete))
}

/// The columns of a point set: positions, attributes (those named in `integer` rounded and marked
/// integer), then `element` when the set has elements.
pub fn columns(set: &PointSet, integer: &[String]) -> Vec<Column> {
    let axes = ["x", "y", "z"];
    let mut out: Vec<Column> = (0..set.dimension)
        .map(|a| Column {
            name: axes[a].to_string(),
            integer: false,
            values: (0..set.len()).map(|i| set.position(i)[a]).collect(),
        })
        .collect();
    for (c, name) in set.attribute_names.iter().enumerate() {
        let is_integer = integer.contains(name);
        let values = (0..set.len())
            .map(|i| set.attributes_of(i)[c])
            .map(|value| if is_integer { value.round() } else { value })
            .collect();
        out.push(Column { name: name.clone(), integer: is_integer, values });
    }
    if let Some(elements) = &set.elements {
        out.push(Column {
            name: "element".into(),
            integer: true,
            values: elements.iter().map(|&e| e as f64).collect(),
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn column(name: &str, integer: bool, values: &[f64]) -> Column {
        Column { name: name.into(), integer, values: values.to_vec() }
    }

    #[test]
    fn columns_round_trip_and_errors_name_the_set() {
        let table = vec![
            column("label", true, &[0.0, 1.0, 1.0]),
            column("x", false, &[0.0, 1.0, 2.0]),
            column("y", false, &[0.5, 0.5, 1.5]),
            column("dbh", false, &[10.0, 22.5, 3.0]),
            column("element", true, &[-1.0, 4.0, 4.0]),
        ];
        let (set, discrete) = point_set(&table, "exemplar").unwrap();
        assert_eq!((set.dimension, set.len(), discrete), (2, 3, vec!["label".to_string()]));
        assert_eq!(set.attribute_names, vec!["label".to_string(), "dbh".to_string()]);
        let back = columns(&set, &["label".to_string()]);
        let names: Vec<&str> = back.iter().map(|c| c.name.as_str()).collect();
        assert_eq!(names, ["x", "y", "label", "dbh", "element"]);
        assert_eq!(back[4].values, vec![-1.0, 4.0, 4.0]);
        assert!(back[2].integer && !back[3].integer);
        let no_y = [column("x", false, &[0.0])];
        assert!(point_set(&no_y, "exemplar").unwrap_err().to_string().contains("x and y"));
        let ragged = [column("x", false, &[0.0, 1.0]), column("y", false, &[0.0])];
        assert!(point_set(&ragged, "existing points").unwrap_err().to_string().contains("existing points"));
        let fractional = [column("x", false, &[0.0]), column("y", false, &[0.0]), column("element", false, &[0.5])];
        assert!(point_set(&fractional, "exemplar").unwrap_err().to_string().contains("whole numbers"));
    }
}
