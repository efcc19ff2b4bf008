//! Times single evaluations of T on the bench's 3D lattice (the merging step's unit of work):
//! `cargo run --release -p motif-points --example evaluate -- [box side, default 14] [repeats, default 3]`.
//! Prints points, quadrature points, the energy (same bytes every run) and the fastest time.

use std::io::Write;

use motif_points::samples::lattice_exemplar;
use motif_points::{Domain, EnergyCase, Evaluator, Input, Params};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut arguments = std::env::args().skip(1);
    let side: f64 = arguments.next().map(|a| a.parse()).transpose()?.unwrap_or(14.0);
    let repeats: usize = arguments.next().map(|a| a.parse()).transpose()?.unwrap_or(3);
    let mut params = Params::default();
    params.neighbourhood = Some(0.75);
    params.seed = 1;
    let domain = Domain::Box { min: vec![0.0; 3], max: vec![side, side, 0.88 * side] };
    let input = Input::new(lattice_exemplar(1100, 1), domain);
    let case = EnergyCase::new(&input, &params)?;
    for attributes in [false, true] {
        let mut best = f64::INFINITY;
        let mut energy = 0.0;
        for _ in 0..repeats {
            let start = std::time::Instant::now();
            energy = case.evaluate(Evaluator::Fast, attributes);
            best = best.min(start.elapsed().as_secs_f64());
        }
        // Written with `?` so a closed pipe (`| head`) ends the program with an error, not a panic.
        writeln!(
            std::io::stdout().lock(),
            "points {} quadrature {} attributes {attributes}: T = {energy:.9e}, {:.1} ms",
            case.points(),
            case.quadrature_points(),
            best * 1000.0
        )?;
    }
    Ok(())
}
