//! The JSON text of every answer, the explorer's and the command line's `--json` alike:
//! serde_json with shortest round-trip floats, and a negative zero written as 0 (its sign
//! carries no information in any result).

use std::io;

use serde::Serialize;
use serde_json::ser::{CompactFormatter, Formatter, PrettyFormatter};

/// The pretty (indented) JSON text of a value.
pub fn pretty<T: Serialize>(v: &T) -> serde_json::Result<String> {
    let mut bytes = Vec::new();
    let mut ser = serde_json::Serializer::with_formatter(&mut bytes, Clean(PrettyFormatter::new()));
    v.serialize(&mut ser)?;
    utf8(bytes)
}

/// The compact JSON text of a value (the explorer's answers).
pub fn compact<T: Serialize>(v: &T) -> serde_json::Result<Vec<u8>> {
    let mut bytes = Vec::new();
    let mut ser = serde_json::Serializer::with_formatter(&mut bytes, Clean(CompactFormatter));
    v.serialize(&mut ser)?;
    Ok(bytes)
}

/// serde_json's bytes as text (they are UTF-8; a failure would be serde_json's own).
fn utf8(bytes: Vec<u8>) -> serde_json::Result<String> {
    String::from_utf8(bytes)
        .map_err(|e| serde_json::Error::io(io::Error::new(io::ErrorKind::InvalidData, e)))
}

/// A serde_json formatter (pretty or compact) with −0 written as 0.
struct Clean<F>(F);

/// Delegates a formatter method to the wrapped formatter.
macro_rules! delegate {
    ($($name:ident$(($arg:ident: $t:ty))?),* $(,)?) => {$(
        fn $name<W: ?Sized + io::Write>(&mut self, w: &mut W $(, $arg: $t)?) -> io::Result<()> {
            self.0.$name(w $(, $arg)?)
        }
    )*};
}

impl<F: Formatter> Formatter for Clean<F> {
    delegate!(
        begin_array,
        end_array,
        begin_array_value(first: bool),
        end_array_value,
        begin_object,
        end_object,
        begin_object_key(first: bool),
        begin_object_value,
        end_object_value,
    );

    fn write_f64<W: ?Sized + io::Write>(&mut self, w: &mut W, v: f64) -> io::Result<()> {
        self.0.write_f64(w, if v == 0.0 { 0.0 } else { v })
    }

    fn write_f32<W: ?Sized + io::Write>(&mut self, w: &mut W, v: f32) -> io::Result<()> {
        self.0.write_f32(w, if v == 0.0 { 0.0 } else { v })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn json_writes_negative_zero_as_zero_and_keeps_key_order() {
        #[derive(Serialize)]
        struct T {
            z: f64,
            a: [f64; 2],
        }
        let text = pretty(&T {
            z: -0.0,
            a: [-0.0, -1.5e-7],
        })
        .unwrap();
        assert!(!text.contains("-0.0"), "{text}");
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert_eq!(v["a"][1].as_f64(), Some(-1.5e-7));
        assert!(text.find("\"z\"") < text.find("\"a\""), "{text}");
    }
}
