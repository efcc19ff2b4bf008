//! Local thickness of a 3D point set: how far points stand off the plane through their nearest
//! neighbours. A sheet or a shell sampled by points is thin (about half a spacing for CGAL's fin,
//! from the roughness of its sampling), a uniform random set is not (about 1.4 spacings): the
//! figure says whether a synthesis kept a 3D structure's layers (issue 35).

use crate::grid::StaticGrid;
use crate::linear::Vector;

/// Nearest neighbours fitted with each point.
const NEIGHBOURS: usize = 12;

/// Mean over points of the root-mean-square distance of a point and its [`NEIGHBOURS`] nearest
/// neighbours from their least-squares plane, in units of `spacing`. 0 for sets outside 3D or
/// with too few points.
pub(crate) fn mean_thickness<const D: usize>(points: &[Vector<D>], spacing: f64) -> f64 {
    if D != 3 || points.len() <= NEIGHBOURS || spacing <= 0.0 {
        return 0.0;
    }
    let grid = StaticGrid::new(points, 3.0 * spacing);
    let mut total = 0.0;
    for (i, p) in points.iter().enumerate() {
        let mut radius = 3.0 * spacing;
        let neighbours = loop {
            let mut found: Vec<(f64, usize)> = Vec::new();
            grid.for_each_within(p, radius, |j, _, d2| {
                if j != i {
                    found.push((d2, j));
                }
            });
            if found.len() >= NEIGHBOURS || radius > 1e3 * spacing {
                found.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
                found.truncate(NEIGHBOURS);
                break found;
            }
            radius *= 2.0;
        };
        let members: Vec<[f64; 3]> = std::iter::once(i)
            .chain(neighbours.iter().map(|&(_, j)| j))
            .map(|j| std::array::from_fn(|a| points[j][a]))
            .collect();
        total += smallest_eigenvalue(covariance(&members)).max(0.0).sqrt();
    }
    total / points.len() as f64 / spacing
}

/// The covariance matrix of `points` about their mean.
fn covariance(points: &[[f64; 3]]) -> [[f64; 3]; 3] {
    let n = points.len() as f64;
    let mean: [f64; 3] = std::array::from_fn(|a| points.iter().map(|p| p[a]).sum::<f64>() / n);
    std::array::from_fn(|a| {
        std::array::from_fn(|b| points.iter().map(|p| (p[a] - mean[a]) * (p[b] - mean[b])).sum::<f64>() / n)
    })
}

/// The smallest eigenvalue of a symmetric 3 × 3 matrix, by cyclic Jacobi rotations (square roots
/// only: the same bits natively and in WebAssembly).
fn smallest_eigenvalue(mut m: [[f64; 3]; 3]) -> f64 {
    for _ in 0..32 {
        let off = m[0][1] * m[0][1] + m[0][2] * m[0][2] + m[1][2] * m[1][2];
        let scale = m[0][0] * m[0][0] + m[1][1] * m[1][1] + m[2][2] * m[2][2];
        if off <= 1e-30 * scale.max(1e-300) {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if m[p][q] == 0.0 {
                continue;
            }
            // The rotation that zeroes m[p][q] (Golub and Van Loan, Algorithm 8.5.1).
            let tau = (m[q][q] - m[p][p]) / (2.0 * m[p][q]);
            let t = tau.signum() / (tau.abs() + (1.0 + tau * tau).sqrt());
            let c = 1.0 / (1.0 + t * t).sqrt();
            let s = t * c;
            let mut next = m;
            for k in 0..3 {
                next[k][p] = c * m[k][p] - s * m[k][q];
                next[k][q] = s * m[k][p] + c * m[k][q];
            }
            m = next;
            for k in 0..3 {
                next[p][k] = c * m[p][k] - s * m[q][k];
                next[q][k] = s * m[p][k] + c * m[q][k];
            }
            m = next;
        }
    }
    m[0][0].min(m[1][1]).min(m[2][2])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jacobi_finds_the_smallest_eigenvalue() {
        // Eigenvalues 1, 2 and 4 in a rotated frame.
        let (c, s) = (0.6, 0.8);
        let r = [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]];
        let d = [4.0, 2.0, 1.0];
        let m: [[f64; 3]; 3] =
            std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| r[i][k] * d[k] * r[j][k]).sum()));
        assert!((smallest_eigenvalue(m) - 1.0).abs() < 1e-12, "{}", smallest_eigenvalue(m));
    }

    #[test]
    fn a_plane_is_thin_and_a_cloud_is_not() {
        let plane: Vec<Vector<3>> =
            (0..400).map(|i| [(i % 20) as f64 + 0.3 * ((i * 7) % 5) as f64 / 5.0, (i / 20) as f64, 0.0]).collect();
        assert!(mean_thickness(&plane, 1.0) < 1e-6);
        let cloud: Vec<Vector<3>> =
            (0..1000).map(|i| [(i % 10) as f64, ((i / 10) % 10) as f64, (i / 100) as f64]).collect();
        assert!(mean_thickness(&cloud, 1.0) > 0.3, "{}", mean_thickness(&cloud, 1.0));
        assert_eq!(mean_thickness(&[[0.0, 0.0]; 50], 1.0), 0.0);
    }
}
