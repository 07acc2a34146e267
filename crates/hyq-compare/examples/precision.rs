//! How precise a policy comparison's travel figure is for a given number of episodes: reads a
//! `hyq compare --policy` report.json and, for each engine and each count N of its first
//! episodes, prints the mean travel toward the goal with its 95 % bootstrap interval (seeded
//! with the report's seed, as the report does), the half-width in metres and as a share of the
//! mean, and how many episodes a ±5 % half-width would take (half-width ∝ 1/√N).
//!
//! ```sh
//! cargo run -p hyq-compare --example precision -- docs/comparison/policy/report.json 20,50,100,200
//! ```

use std::process::ExitCode;

use serde_json::Value;

fn main() -> ExitCode {
    match run() {
        Ok(table) => {
            print!("{table}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("precision: {e}");
            ExitCode::from(2)
        }
    }
}

fn run() -> Result<String, String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [path, counts] = args.as_slice() else {
        return Err("usage: precision REPORT.json N1,N2,...".into());
    };
    let counts: Vec<usize> = counts
        .split(',')
        .map(|c| {
            c.trim()
                .parse()
                .map_err(|_| format!("{c:?} is not a count"))
        })
        .collect::<Result<_, _>>()?;
    let text = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
    let report: Value = serde_json::from_str(&text).map_err(|e| format!("{path}: {e}"))?;
    let seed = report["seed"].as_u64().ok_or(format!("{path}: no seed"))?;
    let sides = report["sides"]
        .as_array()
        .ok_or(format!("{path}: no sides"))?;
    let mut out = String::from(
        "| engine | episodes | travel (m), mean [95 % CI] | half-width (m) | half-width / mean | episodes for ±5 % |\n|---|---|---|---|---|---|\n",
    );
    for side in sides {
        let label = side["label"].as_str().unwrap_or("?");
        let travel: Vec<f64> = side["episodes"]
            .as_array()
            .ok_or(format!("{path}: {label} has no episodes"))?
            .iter()
            .map(|e| e["travel_m"].as_f64().unwrap_or(f64::NAN))
            .collect();
        for &n in &counts {
            if n == 0 || n > travel.len() {
                continue;
            }
            let e = hyq_stats::mean_ci(&travel[..n], seed).map_err(|e| format!("{label}: {e}"))?;
            let share = e.half_width() / e.mean.abs();
            let needed = (n as f64 * (share / 0.05).powi(2)).ceil();
            out.push_str(&format!(
                "| {label} | {n} | {:.3} [{:.3}, {:.3}] | {:.3} | {:.1} % | {needed} |\n",
                e.mean,
                e.ci95[0],
                e.ci95[1],
                e.half_width(),
                100.0 * share
            ));
        }
    }
    Ok(out)
}
