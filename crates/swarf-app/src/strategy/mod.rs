//! The strategies a job can name: one [`Strategy`] enum, a variant per strategy,
//! each holding the parameter struct of the crate that owns the strategy (the job
//! file's `[strategy]` table for that `kind`), and one [`Kind`] impl per strategy
//! saying what the job pipeline asks of it: its name, its finishing part, its
//! checks and its plan.
//!
//! Adding a strategy is its kernel's parameter struct and plan, one file here with
//! its [`Kind`] impl, and one line in the `strategies!` list: the enum, its file
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
pub(crate) mod schema;

pub use schema::{fields_of, kinds_taking};

use crate::plan::PlanInput;
use serde::Serialize;
use serde::de::DeserializeOwned;
use std::fmt::Debug;
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
    type Params: Clone
        + PartialEq
        + Debug
        + Default
        + Serialize
        + DeserializeOwned
        + schemars::JsonSchema;
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
}

/// The enum of strategies `$name` with a variant per listed [`Kind`], its file
/// syntax (serde), its schema (`$schema`, for the docs and the messages) and every
/// dispatch over them. [`Strategy`] is the list of every strategy.
macro_rules! strategies {
    ($(#[$enum_doc:meta])* $vis:vis enum $name:ident, $schema:ident {
        $( $(#[$doc:meta])* $variant:ident => $kind:ty, )*
    }) => {
        $(#[$enum_doc])*
        #[derive(Debug, Clone, PartialEq)]
        $vis enum $name {
            $( $(#[$doc])* $variant(<$kind as $crate::strategy::Kind>::Params), )*
        }

        impl $name {
            /// Every kind, as a job file names it.
            pub const KINDS: &'static [&'static str] =
                &[$( <$kind as $crate::strategy::Kind>::KIND ),*];

            /// The kind, as a job file names it.
            pub fn kind(&self) -> &'static str {
                match self { $( $name::$variant(_) => <$kind as $crate::strategy::Kind>::KIND, )* }
            }

            /// The variant's name (`IsoScallop`), as program comments and sequence
            /// reports write it.
            pub fn name(&self) -> &'static str {
                match self { $( $name::$variant(_) => stringify!($variant), )* }
            }

            /// The tolerance and zigzag.
            pub fn finish(&self) -> &swarf_path::Finish {
                match self { $( $name::$variant(p) => <$kind as $crate::strategy::Kind>::finish(p), )* }
            }

            /// The scallop height the strategy is planned for, mm, when it states one.
            pub fn scallop(&self) -> Option<f64> {
                match self { $( $name::$variant(p) => <$kind as $crate::strategy::Kind>::scallop(p), )* }
            }

            /// Whether the strategy places a tilted tool itself.
            pub fn tilted(&self) -> bool {
                match self { $( $name::$variant(_) => <$kind as $crate::strategy::Kind>::TILTED, )* }
            }

            /// Whether the job's leads apply.
            pub fn leads(&self) -> bool {
                match self { $( $name::$variant(_) => <$kind as $crate::strategy::Kind>::LEADS, )* }
            }

            /// Checks the parameters for `tool`.
            ///
            /// # Errors
            /// The field and what was expected.
            pub fn validate(&self, tool: &swarf_tool::Cutter) -> Result<(), $crate::strategy::FieldError> {
                match self { $( $name::$variant(p) => <$kind as $crate::strategy::Kind>::validate(p, tool), )* }
            }

            /// Plans the strategy with `cutting` on `input`.
            ///
            /// # Errors
            /// The strategy's, naming fields inside the table.
            pub fn plan(
                &self,
                cutting: &swarf_path::Cutting,
                input: $crate::plan::PlanInput<'_>,
            ) -> Result<swarf_path::Plan, swarf_path::PathError> {
                match self { $( $name::$variant(p) => <$kind as $crate::strategy::Kind>::plan(p, cutting, input), )* }
            }

            /// The schema of every kind's table, as JSON.
            pub fn schema() -> &'static serde_json::Value {
                static SCHEMA: std::sync::OnceLock<serde_json::Value> = std::sync::OnceLock::new();
                SCHEMA.get_or_init($crate::strategy::schema::generate::<$schema>)
            }

            /// The strategy of `kind` with the parameters in `table`.
            ///
            /// # Errors
            /// An unknown kind; the table's first bad field (`field: message`).
            pub fn from_table(kind: &str, table: toml::Table) -> Result<$name, String> {
                $( if kind == <$kind as $crate::strategy::Kind>::KIND {
                    return $crate::strategy::schema::decode::<$kind>(table, Self::schema())
                        .map($name::$variant);
                } )*
                Err($crate::strategy::schema::unknown_kind(kind, Self::KINDS))
            }

            /// The parameters as a table, `kind` first.
            fn to_table(&self) -> Result<toml::Table, String> {
                let params = match self {
                    $( $name::$variant(p) => toml::Table::try_from(p), )*
                };
                let mut table = toml::Table::new();
                table.insert("kind".into(), toml::Value::String(self.kind().into()));
                table.extend(params.map_err(|e| e.to_string())?);
                Ok(table)
            }
        }

        /// The schema of every kind's table.
        #[derive(schemars::JsonSchema)]
        #[serde(tag = "kind", rename_all = "kebab-case")]
        #[allow(dead_code)]
        enum $schema {
            $( $(#[$doc])* $variant(<$kind as $crate::strategy::Kind>::Params), )*
        }

        impl<'de> serde::Deserialize<'de> for $name {
            /// `kind`, then the rest of the table as that kind's parameters.
            fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
                let table = toml::Table::deserialize(d)?;
                $crate::strategy::schema::split_kind(table, Self::KINDS)
                    .and_then(|(kind, table)| $name::from_table(&kind, table))
                    .map_err(serde::de::Error::custom)
            }
        }

        impl serde::Serialize for $name {
            /// The table a job file writes: `kind` and the parameters.
            fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                self.to_table()
                    .map_err(serde::ser::Error::custom)?
                    .serialize(s)
            }
        }

        impl schemars::JsonSchema for $name {
            fn schema_name() -> std::borrow::Cow<'static, str> {
                stringify!($name).into()
            }

            fn json_schema(generator: &mut schemars::SchemaGenerator) -> schemars::Schema {
                $schema::json_schema(generator)
            }
        }
    };
}

strategies! {
    /// A job's strategy and its parameters (module doc).
    pub enum Strategy, StrategySchema {
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
}

#[cfg(test)]
mod tests;
