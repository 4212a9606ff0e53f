//! Counters the targets print now and then (at powers of two of the
//! number of inputs), so a campaign's log shows how many inputs were in
//! range and how close the checked errors came to their bounds.

use std::collections::BTreeMap;
use std::sync::Mutex;

static COUNTS: Mutex<BTreeMap<&'static str, u64>> = Mutex::new(BTreeMap::new());
static WORST: Mutex<BTreeMap<&'static str, f64>> = Mutex::new(BTreeMap::new());

/// Counts one input under `what`; every power of two of the total under
/// `"inputs"`, prints all counters with the `target` name.
pub fn count(target: &str, what: &'static str) {
    let mut c = COUNTS.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    *c.entry(what).or_default() += 1;
    if what == "inputs" {
        let n = c["inputs"];
        if n.is_power_of_two() && n >= 1024 {
            let w = WORST.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
            eprintln!("stats: {target} {c:?} worst {w:?}");
        }
    }
}

/// Keeps the largest value seen under `what`.
pub fn worst(what: &'static str, value: f64) {
    let mut w = WORST.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    let e = w.entry(what).or_insert(0.0);
    if value > *e {
        *e = value;
    }
}
