//! The inverse of `arbitrary`'s decoding for the input types, used to write
//! the seed corpus.
//!
//! `arbitrary` 1.x reads an integer as its little-endian bytes (zeros once
//! the data runs out), a `bool` as the low bit of a byte, a derived enum's
//! variant as a `u32` mapped by `(x * count) >> 32`, an array element by
//! element, a derived struct field by field, and a `Vec` not in last
//! position as elements each preceded by a `true` byte, then a `false`
//! byte. Every top-level input type ends with a plain integer field, so
//! the "take the rest" decoding of the last field is the ordinary one.
//! `make_corpus` checks `decode(encode(x)) == x` for every seed it writes,
//! so a change of format fails loudly instead of writing useless seeds.

/// Appends the bytes `arbitrary` decodes back into `self`.
pub trait Encode {
    /// Appends the encoding of `self` to `out`.
    fn encode(&self, out: &mut Vec<u8>);
}

/// The encoding of a whole input.
pub fn to_bytes<E: Encode>(x: &E) -> Vec<u8> {
    let mut out = Vec::new();
    x.encode(&mut out);
    out
}

/// Encodes variant `index` of an enum with `count` variants: the smallest
/// `u32` `x` with `(x * count) >> 32 == index`.
pub fn variant(out: &mut Vec<u8>, index: u64, count: u64) {
    let x = (index << 32).div_ceil(count);
    out.extend_from_slice(&(x as u32).to_le_bytes());
}

macro_rules! ints {
    ($($t:ty),*) => {$(
        impl Encode for $t {
            fn encode(&self, out: &mut Vec<u8>) {
                out.extend_from_slice(&self.to_le_bytes());
            }
        }
    )*};
}
ints!(u8, i8, u16, i16, u32);

impl Encode for bool {
    fn encode(&self, out: &mut Vec<u8>) {
        out.push(u8::from(*self));
    }
}

impl<E: Encode, const N: usize> Encode for [E; N] {
    fn encode(&self, out: &mut Vec<u8>) {
        self.iter().for_each(|x| x.encode(out));
    }
}

impl<E: Encode> Encode for Vec<E> {
    fn encode(&self, out: &mut Vec<u8>) {
        for x in self {
            out.push(1);
            x.encode(out);
        }
        out.push(0);
    }
}

impl<E: Encode> Encode for Option<E> {
    fn encode(&self, out: &mut Vec<u8>) {
        match self {
            None => out.push(0),
            Some(x) => {
                out.push(1);
                x.encode(out);
            }
        }
    }
}

/// Implements [`Encode`] for a struct, field by field in declaration
/// order.
#[macro_export]
macro_rules! encode_struct {
    ($name:ident { $($field:ident),* $(,)? }) => {
        impl $crate::encode::Encode for $name {
            fn encode(&self, out: &mut Vec<u8>) {
                $( $crate::encode::Encode::encode(&self.$field, out); )*
            }
        }
    };
}

/// Implements [`Encode`] for an enum whose variants are unit or hold one
/// or more values: `encode_enum!(Name[count] { 0 => Unit, 1 => Holder(x, y) })`.
#[macro_export]
macro_rules! encode_enum {
    ($name:ident [$count:expr] { $($index:literal => $var:ident $(($($x:ident),+))?),* $(,)? }) => {
        impl $crate::encode::Encode for $name {
            fn encode(&self, out: &mut Vec<u8>) {
                match self {
                    $( $name::$var $(($($x),+))? => {
                        $crate::encode::variant(out, $index, $count);
                        $( $( $crate::encode::Encode::encode($x, out); )+ )?
                    } )*
                }
            }
        }
    };
}

macro_rules! tuples {
    ($(($($n:tt $t:ident),*)),*) => {$(
        impl<$($t: Encode),*> Encode for ($($t,)*) {
            fn encode(&self, out: &mut Vec<u8>) {
                $( self.$n.encode(out); )*
            }
        }
    )*};
}
tuples!((0 A, 1 B), (0 A, 1 B, 2 C), (0 A, 1 B, 2 C, 3 D));

impl<E: Encode> Encode for &E {
    fn encode(&self, out: &mut Vec<u8>) {
        (*self).encode(out);
    }
}
