//! What the playground's points panel starts from, shared by the brushing examples.

/// The built-in hex exemplar, the attributes it snaps (`shade`), its mean spacing and the page's
/// scale: 14 canvas pixels per exemplar spacing (from the bounding box).
pub(crate) fn hex_panel() -> (motif_points::PointSet, Vec<String>, f64, f64) {
    let exemplar = motif_points::samples::hex_exemplar(9, 8, 0.08, 1);
    let (mut low, mut high) = ([f64::MAX; 2], [f64::MIN; 2]);
    for i in 0..exemplar.len() {
        for a in 0..2 {
            low[a] = low[a].min(exemplar.position(i)[a]);
            high[a] = high[a].max(exemplar.position(i)[a]);
        }
    }
    let spacing = ((high[0] - low[0]) * (high[1] - low[1]) / exemplar.len() as f64).sqrt();
    (exemplar, vec!["shade".to_string()], spacing, 14.0 / spacing)
}
