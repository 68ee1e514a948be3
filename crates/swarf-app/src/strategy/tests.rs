//! Tests of the strategy list: a toy strategy added with one [`Kind`] impl and one
//! list entry, the messages for misplaced fields and bad values, and the schema
//! against serde.

use super::{Kind, Strategy};
use crate::plan::PlanInput;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use swarf_geom::Point3;
use swarf_path::{Cutting, Finish, PathError, Plan, PlanReport};
use swarf_tool::{Cutter, Pose};
use swarf_toolpath::{Pass, PathPoint};

/// A toy strategy: one straight pass along +X at a fixed height over the part.
struct Toy;

/// The toy's parameters.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
struct ToyParams {
    #[serde(flatten)]
    finish: Finish,
    /// Height of the pass above the part, mm.
    height: f64,
}

impl Kind for Toy {
    type Params = ToyParams;
    const KIND: &'static str = "toy";

    fn finish(p: &ToyParams) -> &Finish {
        &p.finish
    }

    fn validate(p: &ToyParams, _: &Cutter) -> Result<(), super::FieldError> {
        if p.height >= 0.0 {
            return Ok(());
        }
        Err(super::FieldError {
            field: "height".into(),
            message: "expected a height of 0 or more".into(),
        })
    }

    fn plan(p: &ToyParams, cutting: &Cutting, input: PlanInput<'_>) -> Result<Plan, PathError> {
        let b = match input {
            PlanInput::Mesh(m) => m.aabb(),
            PlanInput::Part(part) => part.tessellate(0.1)?.aabb(),
        };
        let z = b.max.z + p.height;
        let points = [b.min.x, b.max.x]
            .map(|x| PathPoint::new(Pose::vertical(Point3::new(x, b.min.y, z))))
            .to_vec();
        let pass = Pass {
            points,
            ..Pass::default()
        };
        Ok(Plan::from_passes(
            vec![pass],
            cutting,
            PlanReport::default(),
            Vec::new(),
        ))
    }
}

strategies! {
    /// The raster and the toy.
    enum ToyStrategy, ToySchema {
        /// The raster, as in [`Strategy`].
        Raster => super::meshes::Raster,
        /// The toy.
        Toy => Toy,
    }
}

#[test]
fn a_toy_strategy_is_one_kind_impl_and_one_entry() {
    let toy: ToyStrategy = toml::from_str("kind = \"toy\"\nheight = 3\n").unwrap();
    assert_eq!(toy.kind(), "toy");
    assert_eq!(toy.name(), "Toy");
    assert_eq!(toy.finish().tolerance, 0.01);
    assert_eq!(toy.scallop(), None);
    assert!(!toy.tilted() && toy.leads());
    let tool: Cutter = "ball:d=6".parse().unwrap();
    assert!(toy.validate(&tool).is_ok());
    let mesh = swarf_io::builtin_mesh("v-grooves").unwrap();
    let plan = toy
        .plan(&Cutting::new(tool), PlanInput::Mesh(&mesh))
        .unwrap();
    let pass = &plan.toolpath.passes[0];
    assert_eq!(pass.points[0].pose.cl.z, mesh.aabb().max.z + 3.0);
    // Its table is checked like every other: a bad value, a misplaced field.
    let low: ToyStrategy = toml::from_str("kind = \"toy\"\nheight = -1\n").unwrap();
    let e = low.validate(&tool).unwrap_err().in_table("strategy");
    assert_eq!(e, "strategy.height: expected a height of 0 or more");
    let e = toml::from_str::<ToyStrategy>("kind = \"toy\"\nscallop = 1\n")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("scallop: unknown field `scallop` for kind `toy` (it is a field of `raster`)"),
        "{e}"
    );
    // The raster of the same list still reads, and round-trips.
    let raster: ToyStrategy = toml::from_str("kind = \"raster\"\nscallop = 0.1\n").unwrap();
    let back: ToyStrategy = toml::from_str(&toml::to_string(&raster).unwrap()).unwrap();
    assert_eq!(back, raster);
    assert_eq!(ToyStrategy::KINDS, ["raster", "toy"]);
}

#[test]
fn misplaced_fields_name_the_kinds_that_take_them() {
    let e = Strategy::from_table(
        "iso-scallop",
        toml::from_str("scallop = 0.1\noverlap = 2").unwrap(),
    )
    .unwrap_err();
    assert!(
        e.starts_with("overlap: unknown field `overlap` for kind `iso-scallop`"),
        "{e}"
    );
    assert!(
        e.contains("it is a field of `steep-shallow`, `cleanup`"),
        "{e}"
    );
    assert!(
        e.contains("`iso-scallop` takes `direction`, `scallop`, `start`, `tolerance`, `zigzag`"),
        "{e}"
    );
    let e = Strategy::from_table("raster", toml::from_str("spiral = 1").unwrap()).unwrap_err();
    assert!(e.contains("no strategy takes it"), "{e}");
    let e = Strategy::from_table("spiral", toml::Table::new()).unwrap_err();
    assert!(
        e.starts_with("kind: unknown variant `spiral`, expected one of `iso-parametric`"),
        "{e}"
    );
}

#[test]
fn bad_values_name_their_field_and_domain() {
    let e = Strategy::from_table("iso-scallop", toml::from_str("direction = \"w\"").unwrap())
        .unwrap_err();
    assert!(
        e.starts_with("direction: unknown variant `w`, expected `u` or `v`"),
        "{e}"
    );
    let e = Strategy::from_table("raster", toml::from_str("scallop = \"x\"").unwrap()).unwrap_err();
    assert!(e.starts_with("scallop: invalid type: string \"x\""), "{e}");
    let e = Strategy::from_table("waterline", toml::from_str("direction = \"up\"").unwrap())
        .unwrap_err();
    assert!(e.contains("expected `climb` or `conventional`"), "{e}");
    let e = Strategy::from_table("waterline", toml::from_str("direction = \"u\"").unwrap())
        .unwrap_err();
    assert!(e.contains("\"u\" is a parameter direction"), "{e}");
}

/// The schema's fields of every kind are what serde reads: every field serde
/// writes for the default parameters is listed, and every listed field is read (not
/// refused as unknown): the docs and the messages list what the files take.
#[test]
fn the_schema_lists_what_serde_reads() {
    let defaults = [
        Strategy::IsoParametric(Default::default()),
        Strategy::IsoPlanar(Default::default()),
        Strategy::IsoScallop(Default::default()),
        Strategy::Raster(Default::default()),
        Strategy::Waterline(Default::default()),
        Strategy::SteepShallow(Default::default()),
        Strategy::Roughing(Default::default()),
        Strategy::Cleanup(Default::default()),
        Strategy::DropSpin(Default::default()),
    ];
    assert_eq!(defaults.len(), Strategy::KINDS.len());
    for s in defaults {
        let kind = s.kind();
        let listed = super::fields_of(kind);
        let table = toml::Table::try_from(&s).unwrap();
        for key in table.keys().filter(|k| *k != "kind") {
            assert!(
                listed.contains(key),
                "{kind}: {key} is written but not listed"
            );
        }
        for field in &listed {
            let samples = [
                toml::Value::Float(1.0),
                toml::Value::Integer(1),
                toml::Value::Boolean(true),
                toml::Value::String("x".into()),
            ];
            for v in samples {
                let t = toml::Table::from_iter([(field.clone(), v)]);
                if let Err(e) = Strategy::from_table(kind, t) {
                    assert!(!e.contains("unknown field"), "{kind}.{field}: {e}");
                }
            }
        }
        let back: Strategy = toml::from_str(&toml::to_string(&s).unwrap()).unwrap();
        assert_eq!(back, s, "{kind}");
    }
}
