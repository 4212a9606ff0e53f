//! JSON for floats that may be NaN or infinite.
//!
//! JSON has no NaN or infinity, and `serde_json` writes them as `null`,
//! which it then refuses to read back as a number: a run that ended with a
//! NaN position (Linahan's response in a narrow slot) made `runs.json`
//! unreadable for `sweepslide merge`. The lab's metrics therefore write a
//! finite value as a JSON number and a non-finite one as the string
//! `"NaN"`, `"inf"` or `"-inf"`, and read all of these back (and `null` as
//! NaN, as older files have it), bit for bit for every finite value.
//!
//! Use with `#[serde(with = "...")]` on an `f64` ([`number`]), an
//! `Option<f64>` ([`optional`]) or an `[f64; 3]` ([`triple`]) field.

use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// One float as written: a number, a string naming a non-finite value, or
/// `null`.
#[derive(Serialize, Deserialize)]
#[serde(untagged)]
enum Repr {
    Number(f64),
    Text(String),
    Null(()),
}

impl Repr {
    fn of(x: f64) -> Self {
        if x.is_finite() {
            Repr::Number(x)
        } else if x.is_nan() {
            Repr::Text("NaN".into())
        } else if x > 0.0 {
            Repr::Text("inf".into())
        } else {
            Repr::Text("-inf".into())
        }
    }

    fn value<E: serde::de::Error>(self) -> Result<f64, E> {
        match self {
            Repr::Number(x) => Ok(x),
            Repr::Null(()) => Ok(f64::NAN),
            Repr::Text(s) => match s.as_str() {
                "NaN" => Ok(f64::NAN),
                "inf" => Ok(f64::INFINITY),
                "-inf" => Ok(f64::NEG_INFINITY),
                _ => Err(E::custom(format!("expected a number, \"NaN\", \"inf\" or \"-inf\", got \"{s}\""))),
            },
        }
    }
}

/// An `f64` field.
pub mod number {
    use super::{Deserialize, Deserializer, Repr, Serialize, Serializer};

    /// Writes `x` (see the module docs).
    ///
    /// # Errors
    /// The serializer's.
    #[allow(clippy::trivially_copy_pass_by_ref)]
    pub fn serialize<S: Serializer>(x: &f64, s: S) -> Result<S::Ok, S::Error> {
        Repr::of(*x).serialize(s)
    }

    /// Reads a value written by [`serialize`] (or `null`, as NaN).
    ///
    /// # Errors
    /// Anything else.
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        Repr::deserialize(d)?.value()
    }
}

/// An `Option<f64>` field: `None` is `null`, so a NaN inside is `"NaN"`.
pub mod optional {
    use super::{Deserialize, Deserializer, Repr, Serialize, Serializer};

    /// Writes `x` (see the module docs).
    ///
    /// # Errors
    /// The serializer's.
    pub fn serialize<S: Serializer>(x: &Option<f64>, s: S) -> Result<S::Ok, S::Error> {
        x.map(Repr::of).serialize(s)
    }

    /// Reads a value written by [`serialize`].
    ///
    /// # Errors
    /// Anything else.
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f64>, D::Error> {
        match Option::<Repr>::deserialize(d)? {
            None | Some(Repr::Null(())) => Ok(None),
            Some(r) => r.value().map(Some),
        }
    }
}

/// An `[f64; 3]` field (a position).
pub mod triple {
    use super::{Deserialize, Deserializer, Repr, Serialize, Serializer};

    /// Writes `v` (see the module docs).
    ///
    /// # Errors
    /// The serializer's.
    pub fn serialize<S: Serializer>(v: &[f64; 3], s: S) -> Result<S::Ok, S::Error> {
        v.map(Repr::of).serialize(s)
    }

    /// Reads a value written by [`serialize`] (or `null`s, as NaN).
    ///
    /// # Errors
    /// Anything else.
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<[f64; 3], D::Error> {
        let [x, y, z] = <[Repr; 3]>::deserialize(d)?;
        Ok([x.value()?, y.value()?, z.value()?])
    }
}

#[cfg(test)]
mod tests {
    use serde::{Deserialize, Serialize};

    #[derive(Serialize, Deserialize, Debug)]
    struct S {
        #[serde(with = "super::number")]
        a: f64,
        #[serde(with = "super::optional")]
        b: Option<f64>,
        #[serde(with = "super::triple")]
        c: [f64; 3],
    }

    fn same(x: f64, y: f64) -> bool {
        x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan())
    }

    #[test]
    fn non_finite_values_round_trip_and_finite_ones_keep_their_bits() {
        for (a, b, c) in [
            (f64::NAN, Some(f64::INFINITY), [f64::NEG_INFINITY, 0.1, -0.0]),
            (1e-308, None, [f64::MAX, f64::MIN_POSITIVE, 5e-324]),
            (-3.25, Some(f64::NAN), [f64::NAN; 3]),
        ] {
            let text = serde_json::to_string(&S { a, b, c }).unwrap();
            let back: S = serde_json::from_str(&text).unwrap();
            assert!(same(back.a, a), "{text}");
            assert_eq!(back.b.is_some(), b.is_some(), "{text}");
            assert!(back.b.zip(b).is_none_or(|(x, y)| same(x, y)), "{text}");
            assert!((0..3).all(|i| same(back.c[i], c[i])), "{text}");
        }
        let text = serde_json::to_string(&S { a: f64::NAN, b: None, c: [f64::INFINITY, 1.0, 2.0] }).unwrap();
        assert_eq!(text, r#"{"a":"NaN","b":null,"c":["inf",1.0,2.0]}"#);
    }

    /// Every finite value reads back with its bits: `serde_json`'s default
    /// parser is off by one unit in the last place for some decimals (such
    /// as `1.9866666666666666`, a final position in the quick report), which
    /// made a merged report differ from the unsharded one; the
    /// `float_roundtrip` feature parses them correctly.
    #[test]
    fn many_finite_values_keep_their_bits() {
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        let mut values = vec![1.986_666_666_666_666_6, 19.992_958_678_214_162, 13.185_200_950_432_975];
        for _ in 0..20_000 {
            // xorshift: bit patterns of every magnitude.
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let v = f64::from_bits(x);
            values.push(if v.is_finite() { v } else { f64::from_bits(x >> 2) });
        }
        for chunk in values.chunks(3) {
            let c = [chunk[0], chunk[chunk.len() / 2], chunk[chunk.len() - 1]];
            let text = serde_json::to_string(&S { a: c[1], b: Some(c[2]), c }).unwrap();
            let back: S = serde_json::from_str(&text).unwrap();
            assert!(same(back.a, c[1]) && back.b.is_some_and(|b| same(b, c[2])), "{text}");
            assert!((0..3).all(|i| same(back.c[i], c[i])), "{text}");
        }
    }

    #[test]
    fn null_reads_as_nan_and_other_strings_are_rejected() {
        let s: S = serde_json::from_str(r#"{"a":null,"b":null,"c":[null,1,"-inf"]}"#).unwrap();
        assert!(s.a.is_nan() && s.b.is_none() && s.c[0].is_nan() && s.c[2] == f64::NEG_INFINITY);
        let e = serde_json::from_str::<S>(r#"{"a":"nan?","b":null,"c":[0,0,0]}"#).unwrap_err();
        assert!(e.to_string().contains("expected a number"), "{e}");
    }
}
