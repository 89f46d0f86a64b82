//! A queue record's specification as the generators read it ([`QueueField`],
//! [`QueueRecord`]), and [`queue_records!`](crate::queue_records), which declares the CPU's
//! structures of arrays (one `Vec` a field) with their records from the one-line-a-field
//! table in `tracer::wavefront::queues`.

/// One field of a queue record: its name (the Rust `Vec`'s and, after the record's
/// region, the WGSL accessors'), its WGSL type, the lanes it takes (`"W.xyz"` groups:
/// vec4 `W` of the record, those components, in the order of the type's components) and
/// the `#if` condition under which the WGSL has it (`None`: always).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct QueueField {
    pub name: &'static str,
    pub wgsl: &'static str,
    pub lanes: &'static str,
    pub condition: Option<&'static str>,
}

/// A queue record: its Rust structure's name and its fields in declaration order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct QueueRecord {
    pub rust: &'static str,
    pub fields: &'static [QueueField],
    /// The WGSL struct whose members are the fields in order, where there is one (the
    /// accessors then also load the record as it: `load_<region>`).
    pub wgsl_struct: Option<&'static str>,
}

/// The `#if` condition of the fields that only scenes with refraction (the tree form of
/// the wavefront) have: they change the record's stride, the others only leave lanes
/// unwritten.
pub const TREE_CONDITION: &str = "REFRACTION";

/// Declares the queue records: for each, a structure of arrays with one `Vec` a field
/// (with `len`, `resize`, `clear`, `reset`) and its [`QueueRecord`] (`RECORD`), field by field
/// `name: RustType = default => "wgsl type" at "lanes" [if "CONDITION"]`.
#[macro_export]
macro_rules! queue_records {
    ($(
        $(#[$doc:meta])*
        $name:ident $(as $wgsl_struct:literal)? {
            $(
                $(#[$field_doc:meta])*
                $field:ident: $rust:ty = $default:expr => $wgsl:literal at $lanes:literal $(if $condition:literal)?,
            )+
        }
    )*) => {
        $(
            $(#[$doc])*
            #[derive(Clone, Debug, Default)]
            pub struct $name {
                $(
                    $(#[$field_doc])*
                    pub $field: Vec<$rust>,
                )+
            }

            impl $name {
                /// The record as the queue specification gives it.
                pub const RECORD: $crate::tracer::wavefront::queues::QueueRecord = $crate::tracer::wavefront::queues::QueueRecord {
                    rust: stringify!($name),
                    fields: &[$(
                        $crate::tracer::wavefront::queues::QueueField {
                            name: stringify!($field),
                            wgsl: $wgsl,
                            lanes: $lanes,
                            condition: $crate::queue_records!(@condition $($condition)?),
                        },
                    )+],
                    wgsl_struct: $crate::queue_records!(@condition $($wgsl_struct)?),
                };

                /// Entries (every field has one a entry).
                pub fn len(&self) -> usize {
                    let lens = [$(self.$field.len()),+];
                    debug_assert!(lens.iter().all(|&n| n == lens[0]), "fields of unequal length");
                    lens[0]
                }

                pub fn is_empty(&self) -> bool {
                    self.len() == 0
                }

                /// Room for `len` entries: new ones take each field's default.
                pub fn resize(&mut self, len: usize) {
                    $(self.$field.resize(len, $default);)+
                }

                /// No entries.
                pub fn clear(&mut self) {
                    $(self.$field.clear();)+
                }

                /// `len` entries, each field's default.
                pub fn reset(&mut self, len: usize) {
                    self.clear();
                    self.resize(len);
                }
            }
        )*

    };
    (@condition) => { None };
    (@condition $condition:literal) => { Some($condition) };
}
