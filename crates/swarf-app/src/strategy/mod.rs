//! The strategies a job can name: one [`Strategy`] enum, a variant per strategy,
//! each holding the parameter struct of the crate that owns the strategy (the job
//! file's `[strategy]` table for that `kind`), and one [`Kind`] impl per strategy
//! saying what the job pipeline asks of it: its name, its finishing part, its
//! checks and its plan.
//!
//! Adding a strategy is its kernel's parameter struct and plan, one file here with
//! its [`Kind`] impl, and one line in the [`strategies!`] list: the enum, its file
//! syntax (`kind = "..."` and the table's fields, unknown fields refused with the
//! kinds that take them), its schema and every dispatch follow from the list.
//!
//! A strategy table is read in two steps: its `kind`, then the rest as that kind's
//! parameters, so that an error names the field inside the table
//! (`scallop: invalid type ...`) and an unknown field the kinds that do take it.

mod cleanup;
mod drop_spin;
mod iso;
mod meshes;
mod roughing;
mod schema;

pub(crate) use schema::unknown_field_name;
pub use schema::{fields_of, kinds_taking};

use crate::plan::PlanInput;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::fmt::Debug;
use swarf_path::strategy::iso::pass_bound::Feed;
use swarf_path::{Cutting, Finish, PathError, Plan};
use swarf_tool::Cutter;

/// A parameter of a strategy table and what is wrong with it: `field` is its name
/// inside the table (empty: the table itself).
#[derive(Debug, Clone, PartialEq)]
pub struct FieldError {
    /// The field, as the table names it.
    pub field: String,
    /// What was expected.
    pub message: String,
}

impl FieldError {
    /// The error placed in `table` (`strategy.scallop: ...`, or `strategy: ...` for
    /// the table itself).
    pub fn in_table(&self, table: &str) -> String {
        format!("{}: {}", place(table, &self.field), self.message)
    }
}

/// `field` of `table` as a job names it: `table.field`, or `table` for the table.
pub fn place(table: &str, field: &str) -> String {
    if field.is_empty() {
        table.to_string()
    } else {
        format!("{table}.{field}")
    }
}

impl From<PathError> for FieldError {
    fn from(e: PathError) -> Self {
        match e {
            PathError::InvalidParameter { field, message } => FieldError { field, message },
            other => FieldError {
                field: String::new(),
                message: other.to_string(),
            },
        }
    }
}

impl From<swarf_rest::RestError> for FieldError {
    fn from(e: swarf_rest::RestError) -> Self {
        match e.field() {
            Some((field, message)) => FieldError {
                field: field.to_string(),
                message,
            },
            None => FieldError {
                field: String::new(),
                message: e.to_string(),
            },
        }
    }
}

impl From<swarf_fiveaxis::FiveAxisError> for FieldError {
    fn from(e: swarf_fiveaxis::FiveAxisError) -> Self {
        match e {
            swarf_fiveaxis::FiveAxisError::InvalidParameter { field, message } => {
                FieldError { field, message }
            }
            other => FieldError {
                field: String::new(),
                message: other.to_string(),
            },
        }
    }
}

/// One strategy as the job pipeline runs it (module doc). Errors name fields inside
/// the strategy table; the caller places them.
pub trait Kind {
    /// The parameters: the strategy table's fields (less `kind`).
    type Params: Clone + PartialEq + Debug + Default + Serialize + DeserializeOwned + schemars::JsonSchema;
    /// The `kind` a job file names it by.
    const KIND: &'static str;
    /// Whether the strategy places a tilted tool itself (no positioning, a machine
    /// for G-code).
    const TILTED: bool = false;
    /// Whether the job's lead arcs and ramps apply to its passes.
    const LEADS: bool = true;

    /// The tolerance and zigzag of `p`.
    fn finish(p: &Self::Params) -> &Finish;

    /// The scallop height `p` is planned for, mm, when it states one.
    fn scallop(_p: &Self::Params) -> Option<f64> {
        None
    }

    /// Checks `p` for the job's `tool`.
    ///
    /// # Errors
    /// The field out of its domain, or inconsistent with the others.
    fn validate(p: &Self::Params, tool: &Cutter) -> Result<(), FieldError>;

    /// Plans `p` with `cutting` on `input`.
    ///
    /// # Errors
    /// The strategy's errors, naming fields inside the table.
    fn plan(p: &Self::Params, cutting: &Cutting, input: PlanInput<'_>) -> Result<Plan, PathError>;

    /// The feed direction of an iso strategy's passes, for the pass bound.
    fn pass_feed(_p: &Self::Params) -> Option<Feed> {
        None
    }
}

/// The variant of [`Strategy`] per strategy, in the order the kinds are listed,
/// with every dispatch over them.
macro_rules! strategies {
    ($( $(#[$doc:meta])* $variant:ident => $kind:ty, )*) => {
        /// A job's strategy and its parameters (module doc).
        #[derive(Debug, Clone, PartialEq)]
        pub enum Strategy {
            $( $(#[$doc])* $variant(<$kind as Kind>::Params), )*
        }

        impl Strategy {
            /// Every kind, as a job file names it.
            pub const KINDS: &'static [&'static str] = &[$( <$kind as Kind>::KIND ),*];

            /// The kind, as a job file names it.
            pub fn kind(&self) -> &'static str {
                match self { $( Strategy::$variant(_) => <$kind as Kind>::KIND, )* }
            }

            /// The variant's name (`IsoScallop`), as program comments and sequence
            /// reports write it.
            pub fn name(&self) -> &'static str {
                match self { $( Strategy::$variant(_) => stringify!($variant), )* }
            }

            /// The tolerance and zigzag.
            pub fn finish(&self) -> &Finish {
                match self { $( Strategy::$variant(p) => <$kind as Kind>::finish(p), )* }
            }

            /// The scallop height the strategy is planned for, mm, when it states one.
            pub fn scallop(&self) -> Option<f64> {
                match self { $( Strategy::$variant(p) => <$kind as Kind>::scallop(p), )* }
            }

            /// Whether the strategy places a tilted tool itself.
            pub fn tilted(&self) -> bool {
                match self { $( Strategy::$variant(_) => <$kind as Kind>::TILTED, )* }
            }

            /// Whether the job's leads apply.
            pub fn leads(&self) -> bool {
                match self { $( Strategy::$variant(_) => <$kind as Kind>::LEADS, )* }
            }

            /// Checks the parameters for `tool`.
            ///
            /// # Errors
            /// The field and what was expected.
            pub fn validate(&self, tool: &Cutter) -> Result<(), FieldError> {
                match self { $( Strategy::$variant(p) => <$kind as Kind>::validate(p, tool), )* }
            }

            /// Plans the strategy with `cutting` on `input`.
            ///
            /// # Errors
            /// The strategy's, naming fields inside the table.
            pub fn plan(&self, cutting: &Cutting, input: PlanInput<'_>) -> Result<Plan, PathError> {
                match self { $( Strategy::$variant(p) => <$kind as Kind>::plan(p, cutting, input), )* }
            }

            /// The feed of an iso strategy's passes, for the pass bound.
            pub fn pass_feed(&self) -> Option<Feed> {
                match self { $( Strategy::$variant(p) => <$kind as Kind>::pass_feed(p), )* }
            }

            /// The strategy of `kind` with the parameters in `table`.
            ///
            /// # Errors
            /// An unknown kind; the table's first bad field (`field: message`).
            pub fn from_table(kind: &str, table: toml::Table) -> Result<Strategy, String> {
                $( if kind == <$kind as Kind>::KIND {
                    return schema::decode::<$kind>(table).map(Strategy::$variant);
                } )*
                Err(schema::unknown_kind(kind))
            }

            /// The parameters as a table, `kind` first.
            fn to_table(&self) -> Result<toml::Table, String> {
                let params = match self {
                    $( Strategy::$variant(p) => toml::Table::try_from(p), )*
                };
                let mut table = toml::Table::new();
                table.insert("kind".into(), toml::Value::String(self.kind().into()));
                table.extend(params.map_err(|e| e.to_string())?);
                Ok(table)
            }
        }

        /// The schema of every kind's table (what [`schema`] documents).
        #[derive(schemars::JsonSchema)]
        #[serde(tag = "kind", rename_all = "kebab-case")]
        #[allow(dead_code)]
        enum StrategySchema {
            $( $(#[$doc])* $variant(<$kind as Kind>::Params), )*
        }
    };
}

strategies! {
    /// Passes along constant-parameter curves of each patch (paper 004).
    IsoParametric => iso::IsoParametric,
    /// Sections of the part by parallel vertical drive planes (paper 004).
    IsoPlanar => iso::IsoPlanar,
    /// Each pass placed so that the scallop to the previous one is the limit (paper
    /// 004).
    IsoScallop => iso::IsoScallop,
    /// Drop-cutter raster on a triangle mesh (iso-planar for meshes).
    Raster => meshes::Raster,
    /// Closed passes at constant heights around the part.
    Waterline => meshes::Waterline,
    /// Raster on the shallow areas, waterline on the steep ones.
    SteepShallow => meshes::SteepShallow,
    /// Z-level roughing from a box stock down to the part plus an allowance.
    Roughing => roughing::Roughing,
    /// Cleanup of the rest material a parent job leaves (thesis 002).
    Cleanup => cleanup::Cleanup,
    /// Five-axis multipoint passes along the common edge of two faces, by drop and
    /// spin (paper 003).
    DropSpin => drop_spin::DropSpin,
}

impl<'de> Deserialize<'de> for Strategy {
    /// `kind`, then the rest of the table as that kind's parameters (module doc).
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        use serde::de::Error;
        let mut table = toml::Table::deserialize(d)?;
        let kind = match table.remove("kind") {
            Some(toml::Value::String(k)) => k,
            Some(v) => {
                return Err(D::Error::custom(format!(
                    "kind: expected one of {}, found {v}",
                    schema::kind_list()
                )));
            }
            None => return Err(D::Error::custom("missing field `kind`")),
        };
        Strategy::from_table(&kind, table).map_err(D::Error::custom)
    }
}

impl Serialize for Strategy {
    /// The table a job file writes: `kind` and the parameters.
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        self.to_table()
            .map_err(serde::ser::Error::custom)?
            .serialize(s)
    }
}

impl schemars::JsonSchema for Strategy {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "Strategy".into()
    }

    fn json_schema(generator: &mut schemars::SchemaGenerator) -> schemars::Schema {
        StrategySchema::json_schema(generator)
    }
}

#[cfg(test)]
mod tests;
