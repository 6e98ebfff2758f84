//! A pyramid of boxes, base 20 (210 boxes), left to stand for 10 s.
//!
//! Run: `cargo run --release --example pyramid [-- --record pyramid.rrec --gif pyramid.gif]`

#![allow(clippy::print_stdout, reason = "an example prints its results")]

mod support;

use rebound_suite::demos::{DT, pyramid};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let pyramid::Pyramid { mut world, boxes } = pyramid::build()?;
    let mut output = support::Output::start(&world, &pyramid::ABOUT)?;
    let base = pyramid::BASE;
    let top = boxes.last().map(|(b, _)| *b);
    let start = std::time::Instant::now();
    let mut worst_step = std::time::Duration::ZERO;
    for _ in 0..600 {
        worst_step = worst_step.max(output.step(&mut world, DT)?.profile.total);
    }
    let elapsed = start.elapsed().as_secs_f64() * 1000.0;
    let drift = boxes
        .iter()
        .filter_map(|(b, p0)| world.body(*b).map(|body| (body.position() - *p0).length()))
        .fold(0.0f32, f32::max);
    let top_drop = top
        .and_then(|t| world.body(t))
        .map_or(f32::NAN, |b| 0.5 + (base - 1) as f32 - b.position().y);
    let asleep = boxes
        .iter()
        .filter(|(b, _)| world.is_sleeping(*b) == Some(true))
        .count();
    println!(
        "pyramid of {} boxes (base {base}) after 10 s at 60 Hz:",
        boxes.len()
    );
    println!(
        "  largest displacement of any box: {:.1} mm",
        drift * 1000.0
    );
    println!(
        "  top box dropped by:              {:.1} mm",
        top_drop * 1000.0
    );
    println!(
        "  boxes asleep:                    {asleep} of {}",
        boxes.len()
    );
    println!(
        "  wall time: {elapsed:.0} ms for 600 steps ({:.2} ms/step average, {:.2} ms worst; recording and \
         drawing included when asked)",
        elapsed / 600.0,
        worst_step.as_secs_f64() * 1000.0
    );
    println!(
        "  standing (every box within 5 cm of its start): {}",
        if drift < 0.05 { "yes" } else { "NO" }
    );
    for line in output.finish()? {
        println!("{line}");
    }
    Ok(())
}
