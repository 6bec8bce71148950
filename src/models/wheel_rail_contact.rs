//! FMU `WheelRailContact`: one wheelset on straight track, both wheels, from wheelset kinematics
//! to creep forces and contact-patch summaries. Variables: `modelDescription/WheelRailContact.json`;
//! physics: [`crate::wheelset`]. A state beyond elastic half-space contact ([`crate::wheelset::validity`])
//! is answered with its outputs and a warning (`fmi2Warning`).

use super::{fastsim_settings, set_outputs};
use crate::damage::record::WearRecord;
use crate::damage::{DamageParams, WearModel};
use crate::fmi::model::{Evaluation, InstanceContext, Model, ModelError, ModelInfo};
use crate::fmi::variables::{IntegerVar, RealVar, Values, VarInfo};
use crate::geometry::groups::MAX_GROUPS;
use crate::geometry::profile::{Profile, ProfileKind};
use crate::geometry::track::TrackSetup;
use crate::material::Material;
use crate::normal::NormalModel;
use crate::tangential::fastsim::Creepage;
use crate::tangential::patch::TangentialModel;
use crate::wheelset::validity::validity;
use crate::wheelset::{
    Creepages, RailInput, SideResult, Slot, TrackInput, Trend, Vertical, WarmStart, Wheelset,
    WheelsetError, WheelsetInput, WheelsetResult, WheelsetSettings, MAX_PATCHES, V_MIN,
};
use std::path::{Path, PathBuf};

/// Generated from `modelDescription/WheelRailContact.json` by `build.rs`.
pub mod generated {
    include!(concat!(env!("OUT_DIR"), "/WheelRailContact_vars.rs"));
}
use generated::var;

pub static INFO: ModelInfo = ModelInfo {
    model_identifier: generated::MODEL_IDENTIFIER,
    guid: generated::GUID,
    model_description_xml: generated::MODEL_DESCRIPTION_XML,
    variables: &generated::VARIABLES,
    counts: generated::COUNTS,
    default_experiment: generated::DEFAULT_EXPERIMENT,
    provides_directional_derivative: generated::PROVIDES_DIRECTIONAL_DERIVATIVE,
    create,
};

fn create(context: &InstanceContext) -> Box<dyn Model> {
    Box::new(WheelRailContact {
        resource_dir: context.resource_dir.clone(),
        solver: None,
        result: WheelsetResult::default(),
        probe_result: WheelsetResult::default(),
        wear: None,
    })
}

struct WheelRailContact {
    resource_dir: Option<PathBuf>,
    solver: Option<Solver>,
    result: WheelsetResult,
    /// The result of the last [`Model::probe`] (directional derivatives).
    probe_result: WheelsetResult,
    /// The wear accumulated over the run (with a `wearModel`; docs/theory.md §10.5).
    wear: Option<WearRecord>,
}

struct Solver {
    wheelset: Wheelset,
    vertical_by_position: bool,
    creepage_prescribed: bool,
}

impl Solver {
    /// Solves the wheelset at the inputs in `values` into `result` and writes the outputs.
    fn solve(
        &mut self,
        values: &mut Values,
        result: &mut WheelsetResult,
    ) -> Result<WheelsetInput, ModelError> {
        let input = input(values, self.vertical_by_position, self.creepage_prescribed);
        match self.wheelset.solve(&input, result) {
            Ok(()) => {}
            Err(WheelsetError::Input(e)) => return Err(e.into()),
            Err(e @ (WheelsetError::NoContact { .. } | WheelsetError::Unbalanced { .. })) => {
                return Err(ModelError::Discard(e.to_string()))
            }
        }
        write_side(values, false, &result.left)?;
        write_side(values, true, &result.right)?;
        Ok(input)
    }
}

/// Creepage change of one difference step of the kinematic inputs (`difference_step`) [-]: deep
/// in the linear part of the creep curves (which bend at creepages of ~1e−3 on a tread), where
/// the creep forces change by ~10 N per step — 1000 times the tolerance of the load balance's
/// creep update (1e−7 of the wheel load).
const CREEPAGE_STEP: f64 = 1e-6;

/// Difference step of the lateral shift and the roll and yaw angles [m, rad]: 1/50 of the contact
/// search's sampling step, so that the reference points move smoothly over it, and a change of the
/// rolling radius (λ ≈ 0.2) of 2 µm — a longitudinal creepage of ~4e−6.
const POSE_STEP: f64 = 1e-5;

/// Lever of the track curvature and of a rail's roll rate on the creepages [m]: a wheel's
/// contact lies ~0.75 m from the track's centre line (Δξ = κ × 0.75 m), and a rail's roll rate
/// moves its contact points with levers of the rail head's size; 1 m keeps the steps
/// [`CREEPAGE_STEP`]-sized.
const CURVATURE_LEVER: f64 = 1.0;

/// Difference step of the prescribed vertical position [m]: 1e−3 of a tread contact's approach
/// (~0.1 mm).
const HEIGHT_STEP: f64 = 1e-7;

/// Difference step of the wheel loads, relative (at least of 1 kN) [-]: 1000 times the load
/// balance's creep tolerance (1e−7 of the load), whose residue would otherwise show in ∂Fz/∂Q
/// (−1 in principle: 0.5 % off at a step of 1e−5 on ANALYN, 0.02 % at 1e−4).
const LOAD_STEP: f64 = 1e-4;

/// Difference step of the prescribed spin creepage [1/m]: the spin's counterpart of
/// [`CREEPAGE_STEP`], φ·a ≈ 6e−7 over a patch's half-length a ≈ 6 mm.
const SPIN_STEP: f64 = 1e-4;

/// Output handles of one patch, in the order of [`patch_values`].
type PatchVars = [RealVar; 26];

fn patch_vars(right: bool, k: usize) -> PatchVars {
    use var::*;
    const LEFT: [PatchVars; MAX_PATCHES] = [
        [
            left_p1_Fn,
            left_p1_Fx,
            left_p1_Fy,
            left_p1_Mz,
            left_p1_area,
            left_p1_pmax,
            left_p1_length,
            left_p1_width,
            left_p1_yRail,
            left_p1_xPos,
            left_p1_yPos,
            left_p1_zPos,
            left_p1_contactAngle,
            left_p1_rollingRadius,
            left_p1_penetration,
            left_p1_xi,
            left_p1_eta,
            left_p1_phi,
            left_p1_adhesionFraction,
            left_p1_frictionalPower,
            left_p1_maxTraction,
            left_p1_Tgamma,
            left_p1_wheelWearRate,
            left_p1_railWearRate,
            left_p1_fatigueIndex,
            left_p1_fatigueIndexLocal,
        ],
        [
            left_p2_Fn,
            left_p2_Fx,
            left_p2_Fy,
            left_p2_Mz,
            left_p2_area,
            left_p2_pmax,
            left_p2_length,
            left_p2_width,
            left_p2_yRail,
            left_p2_xPos,
            left_p2_yPos,
            left_p2_zPos,
            left_p2_contactAngle,
            left_p2_rollingRadius,
            left_p2_penetration,
            left_p2_xi,
            left_p2_eta,
            left_p2_phi,
            left_p2_adhesionFraction,
            left_p2_frictionalPower,
            left_p2_maxTraction,
            left_p2_Tgamma,
            left_p2_wheelWearRate,
            left_p2_railWearRate,
            left_p2_fatigueIndex,
            left_p2_fatigueIndexLocal,
        ],
        [
            left_p3_Fn,
            left_p3_Fx,
            left_p3_Fy,
            left_p3_Mz,
            left_p3_area,
            left_p3_pmax,
            left_p3_length,
            left_p3_width,
            left_p3_yRail,
            left_p3_xPos,
            left_p3_yPos,
            left_p3_zPos,
            left_p3_contactAngle,
            left_p3_rollingRadius,
            left_p3_penetration,
            left_p3_xi,
            left_p3_eta,
            left_p3_phi,
            left_p3_adhesionFraction,
            left_p3_frictionalPower,
            left_p3_maxTraction,
            left_p3_Tgamma,
            left_p3_wheelWearRate,
            left_p3_railWearRate,
            left_p3_fatigueIndex,
            left_p3_fatigueIndexLocal,
        ],
    ];
    const RIGHT: [PatchVars; MAX_PATCHES] = [
        [
            right_p1_Fn,
            right_p1_Fx,
            right_p1_Fy,
            right_p1_Mz,
            right_p1_area,
            right_p1_pmax,
            right_p1_length,
            right_p1_width,
            right_p1_yRail,
            right_p1_xPos,
            right_p1_yPos,
            right_p1_zPos,
            right_p1_contactAngle,
            right_p1_rollingRadius,
            right_p1_penetration,
            right_p1_xi,
            right_p1_eta,
            right_p1_phi,
            right_p1_adhesionFraction,
            right_p1_frictionalPower,
            right_p1_maxTraction,
            right_p1_Tgamma,
            right_p1_wheelWearRate,
            right_p1_railWearRate,
            right_p1_fatigueIndex,
            right_p1_fatigueIndexLocal,
        ],
        [
            right_p2_Fn,
            right_p2_Fx,
            right_p2_Fy,
            right_p2_Mz,
            right_p2_area,
            right_p2_pmax,
            right_p2_length,
            right_p2_width,
            right_p2_yRail,
            right_p2_xPos,
            right_p2_yPos,
            right_p2_zPos,
            right_p2_contactAngle,
            right_p2_rollingRadius,
            right_p2_penetration,
            right_p2_xi,
            right_p2_eta,
            right_p2_phi,
            right_p2_adhesionFraction,
            right_p2_frictionalPower,
            right_p2_maxTraction,
            right_p2_Tgamma,
            right_p2_wheelWearRate,
            right_p2_railWearRate,
            right_p2_fatigueIndex,
            right_p2_fatigueIndexLocal,
        ],
        [
            right_p3_Fn,
            right_p3_Fx,
            right_p3_Fy,
            right_p3_Mz,
            right_p3_area,
            right_p3_pmax,
            right_p3_length,
            right_p3_width,
            right_p3_yRail,
            right_p3_xPos,
            right_p3_yPos,
            right_p3_zPos,
            right_p3_contactAngle,
            right_p3_rollingRadius,
            right_p3_penetration,
            right_p3_xi,
            right_p3_eta,
            right_p3_phi,
            right_p3_adhesionFraction,
            right_p3_frictionalPower,
            right_p3_maxTraction,
            right_p3_Tgamma,
            right_p3_wheelWearRate,
            right_p3_railWearRate,
            right_p3_fatigueIndex,
            right_p3_fatigueIndexLocal,
        ],
    ];
    if right {
        RIGHT[k]
    } else {
        LEFT[k]
    }
}

/// Totals of one side: nPatches, then Fx, Fy, Fz, z, Mx, My, Mz, YQ, Tgamma, wheelWearRate,
/// railWearRate, rcfDamage.
fn side_vars(right: bool) -> (IntegerVar, [RealVar; 15]) {
    use var::*;
    if right {
        (
            right_nPatches,
            [
                right_Fx,
                right_Fy,
                right_Fz,
                right_z,
                right_Mx,
                right_My,
                right_Mz,
                right_YQ,
                right_Tgamma,
                right_wheelWearRate,
                right_railWearRate,
                right_rcfDamage,
                right_rail_Fy,
                right_rail_Fz,
                right_rail_Mx,
            ],
        )
    } else {
        (
            left_nPatches,
            [
                left_Fx,
                left_Fy,
                left_Fz,
                left_z,
                left_Mx,
                left_My,
                left_Mz,
                left_YQ,
                left_Tgamma,
                left_wheelWearRate,
                left_railWearRate,
                left_rcfDamage,
                left_rail_Fy,
                left_rail_Fz,
                left_rail_Mx,
            ],
        )
    }
}

/// A profile parameter: built-in name, or a path. A relative path (a bare file name bundled with
/// `fmu-pack --resource`, typically) is looked up in the FMU's `resources/` first, then in the
/// working directory; when neither holds it, the message lists the places tried. The error names
/// the parameter and its value, then the file, line and reason.
fn load_profile(
    spec: &str,
    kind: ProfileKind,
    smoothing: f64,
    resources: Option<&Path>,
) -> Result<Profile, ModelError> {
    let variable = match kind {
        ProfileKind::Wheel => "wheelProfile",
        ProfileKind::Rail => "railProfile",
    };
    let fail = |e: &dyn std::fmt::Display| ModelError::Error(format!("{variable} = {spec:?}: {e}"));
    let name = spec.trim();
    let builtin = crate::geometry::profile::BUILTIN_NAMES
        .iter()
        .any(|b| b.eq_ignore_ascii_case(name));
    if builtin || name.is_empty() || Path::new(name).is_absolute() {
        return Profile::load(spec, kind, smoothing).map_err(|e| fail(&e));
    }
    let places: Vec<(&str, PathBuf)> = resources
        .map(|dir| ("the FMU's resources folder", dir.join(name)))
        .into_iter()
        .chain(
            std::env::current_dir()
                .ok()
                .map(|dir| ("the working directory", dir.join(name))),
        )
        .collect();
    if let Some((_, path)) = places.iter().find(|(_, p)| p.is_file()) {
        return Profile::from_file(path, Some(kind), smoothing).map_err(|e| fail(&e));
    }
    let e = match Profile::load(spec, kind, smoothing) {
        Ok(profile) => return Ok(profile), // the working directory was not known
        Err(e) => e,
    };
    let looked: Vec<String> = places
        .iter()
        .map(|(place, path)| format!("{place} ({})", path.display()))
        .collect();
    let mut text = format!("{e}; looked in {}", looked.join(" and "));
    if resources.is_none() {
        text.push_str(
            "; there is no resources folder: the host gave no file: URI as resourceLocation",
        );
    }
    Err(fail(&text))
}

/// The wheel and rail profiles the parameters `wheelProfile`, `railProfile` and
/// `profileSmoothing` name (relative paths looked up in `resources` first, then in the working
/// directory).
pub fn profiles(
    values: &Values,
    resources: Option<&Path>,
) -> Result<(Profile, Profile), ModelError> {
    let smoothing = values.real(var::profileSmoothing);
    let load = |name, kind| load_profile(values.string(name), kind, smoothing, resources);
    Ok((
        load(var::wheelProfile, ProfileKind::Wheel)?,
        load(var::railProfile, ProfileKind::Rail)?,
    ))
}

/// The wheelset settings the parameters describe.
pub fn settings(values: &Values) -> Result<WheelsetSettings, ModelError> {
    // The one constraint between parameters (each is range-checked when set): the wheels must
    // fit between the rails.
    let (gauge, flange_backs) = (
        values.real(var::trackGauge),
        values.real(var::flangeBackDistance),
    );
    if flange_backs >= gauge {
        return Err(ModelError::Error(format!(
            "flangeBackDistance = {flange_backs} is outside the allowed range < trackGauge = \
             {gauge} [m]"
        )));
    }
    Ok(WheelsetSettings {
        setup: TrackSetup {
            rail_inclination: values.real(var::railInclination),
            track_gauge: values.real(var::trackGauge),
            flange_back_distance: values.real(var::flangeBackDistance),
            wheel_radius: values.real(var::wheelRadius),
            ..TrackSetup::default()
        },
        material: Material {
            youngs_modulus: values.real(var::E),
            poisson_ratio: values.real(var::nu),
            friction: values.real(var::mu),
        },
        fastsim: fastsim_settings(
            values.integer(var::tractionBound),
            values.integer(var::flexibility),
            values.integer(var::nx),
            values.integer(var::ny),
            values.integer(var::fastsimScheme),
        )?,
        scan_step: values.real(var::scanStep),
        b_min: values.real(var::bMin),
        normal_model: model_code(
            "normalModel",
            values.integer(var::normalModel),
            NormalModel::from_code,
        )?,
        strips: usize::try_from(values.integer(var::nStrips)).unwrap_or(0),
        b_smoothing: values.real(var::bSmoothing),
        kp_shape_correction: values.boolean(var::kpShapeCorrection),
        tangential: model_code(
            "tangentialModel",
            values.integer(var::tangentialModel),
            TangentialModel::from_code,
        )?,
        planar_patch: values.boolean(var::planarPatch),
        reuse_tangential: true,
        damage: damage_params(values)?,
    })
}

/// The damage outputs' parameters (each range-checked when set).
fn damage_params(values: &Values) -> Result<DamageParams, ModelError> {
    let params = DamageParams {
        wear_model: model_code(
            "wearModel",
            values.integer(var::wearModel),
            WearModel::from_code,
        )?,
        wheel_hardness: values.real(var::wheelHardness),
        rail_hardness: values.real(var::railHardness),
        shear_yield_strength: values.real(var::shearYieldStrength),
    };
    params
        .validate()
        .map_err(|e| ModelError::Error(e.to_string()))?;
    Ok(params)
}

/// The model that the integer parameter `name` selects by `code` (`from_code`); any other code
/// is an error quoting the variable table's range.
fn model_code<T>(
    name: &str,
    code: i32,
    from_code: impl Fn(i32) -> Option<T>,
) -> Result<T, ModelError> {
    from_code(code).ok_or_else(|| {
        let allowed = INFO.variable(name).map_or("", |v| v.allowed);
        ModelError::Error(format!(
            "{name} = {code} is outside the allowed range {allowed}"
        ))
    })
}

/// Wheel loads below this count as a lifted wheel (0) [N]. Far below any load that matters, it
/// keeps the load iteration away from loads so small that its first approach underflows to zero
/// (a load of 5e−324 N made `fmi2DoStep` loop forever: docs/reliability.md).
pub const MIN_WHEEL_LOAD: f64 = 1e-6;

/// The wheelset input the inputs describe (`verticalMode` = 2 → `vertical_by_position`,
/// `creepageMode` = 2 → `creepage_prescribed`). Loads below [`MIN_WHEEL_LOAD`] are 0.
pub fn input(
    values: &Values,
    vertical_by_position: bool,
    creepage_prescribed: bool,
) -> WheelsetInput {
    let vx = values.real(var::vx);
    WheelsetInput {
        y: values.real(var::y),
        yaw: values.real(var::yaw),
        roll: values.real(var::roll),
        vertical: if vertical_by_position {
            Vertical::Position {
                z: values.real(var::z),
            }
        } else {
            let load = |q: f64| if q < MIN_WHEEL_LOAD { 0.0 } else { q };
            Vertical::Loads {
                left: load(values.real(var::Qleft)),
                right: load(values.real(var::Qright)),
            }
        },
        creepages: if creepage_prescribed {
            Creepages::Prescribed {
                creepage: Creepage {
                    xi: values.real(var::xi),
                    eta: values.real(var::eta),
                    phi: values.real(var::phi),
                },
                vx,
            }
        } else {
            Creepages::Kinematic {
                vx,
                vy: values.real(var::vy),
                yaw_rate: values.real(var::yawRate),
                omega: values.real(var::omega),
            }
        },
        track: TrackInput {
            curvature: values.real(var::trackCurvature),
            left: rail_input(values, &RAIL_VARS[0]),
            right: rail_input(values, &RAIL_VARS[1]),
        },
    }
}

/// The rails' inputs, left and right, in [`RailInput`]'s order (dy, dz, roll, vy, vz,
/// rollRate).
const RAIL_VARS: [[RealVar; 6]; 2] = {
    use var::*;
    [
        [
            left_rail_dy,
            left_rail_dz,
            left_rail_roll,
            left_rail_vy,
            left_rail_vz,
            left_rail_rollRate,
        ],
        [
            right_rail_dy,
            right_rail_dz,
            right_rail_roll,
            right_rail_vy,
            right_rail_vz,
            right_rail_rollRate,
        ],
    ]
};

fn rail_input(values: &Values, vars: &[RealVar; 6]) -> RailInput {
    let [dy, dz, roll, vy, vz, roll_rate] = vars.map(|v| values.real(v));
    RailInput {
        dy,
        dz,
        roll,
        vy,
        vz,
        roll_rate,
    }
}

fn write_side(values: &mut Values, right: bool, side: &SideResult) -> Result<(), ModelError> {
    let (n, totals) = side_vars(right);
    values.set_integer(n, side.n_patches as i32);
    let [fx, fy, fz] = side.force;
    let [mx, my, mz] = side.moment;
    let total_values = [
        fx,
        fy,
        fz,
        side.z,
        mx,
        my,
        mz,
        side.derailment_quotient,
        side.t_gamma,
        side.wheel_wear_rate,
        side.rail_wear_rate,
        side.rcf_damage,
        side.rail_force[1],
        side.rail_force[2],
        side.rail_moment_x,
    ];
    set_outputs(values, totals, total_values)?;
    for k in 0..MAX_PATCHES {
        let p = &side.patches[k];
        let xs = [
            p.fn_,
            p.fx,
            p.fy,
            p.mz,
            p.area,
            p.pmax,
            p.length,
            p.width,
            p.y_rail,
            p.position[0],
            p.position[1],
            p.position[2],
            p.contact_angle,
            p.rolling_radius,
            p.penetration,
            p.creepage.xi,
            p.creepage.eta,
            p.creepage.phi,
            p.adhesion_fraction,
            p.frictional_power,
            p.max_traction,
            p.t_gamma,
            p.wheel_wear_rate,
            p.rail_wear_rate,
            p.fatigue_index,
            p.fatigue_index_local,
        ];
        set_outputs(values, patch_vars(right, k), xs)?;
    }
    Ok(())
}

impl Model for WheelRailContact {
    fn initialize(&mut self, values: &Values) -> Result<(), ModelError> {
        let (wheel, rail) = profiles(values, self.resource_dir.as_deref())?;
        let wheelset = Wheelset::new(&wheel, &rail, settings(values)?)
            .map_err(|e| ModelError::Error(e.to_string()))?;
        let output = values.string(var::wearOutput);
        let wear_on = wheelset.settings().damage.element_wise();
        if !output.is_empty() && !wear_on {
            return Err(ModelError::Error(format!(
                "wearOutput = {output:?} needs a wear model: wearModel = {} (0 computes no wear)",
                values.integer(var::wearModel)
            )));
        }
        self.wear = wear_on.then(|| {
            let [left, right] = wheelset.wear_rates();
            WearRecord::new(
                [[&left.wheel, &left.rail], [&right.wheel, &right.rail]],
                values.real(var::wheelRadius),
            )
        });
        self.solver = Some(Solver {
            wheelset,
            vertical_by_position: values.integer(var::verticalMode) == 2,
            creepage_prescribed: values.integer(var::creepageMode) == 2,
        });
        Ok(())
    }

    fn evaluate(&mut self, values: &mut Values, _time: f64) -> Result<Evaluation, ModelError> {
        let solver = self.solver.as_mut().ok_or_else(not_initialized)?;
        let input = solver.solve(values, &mut self.result)?;
        write_wear_record(values, self.wear.as_ref())?;
        Ok(match validity(&self.result) {
            None => Evaluation::Ok,
            Some(implausible) => Evaluation::Warning(implausible.message(&input.vertical)),
        })
    }

    /// Adds the step's wear (the rates of its evaluation across the profiles times the distance
    /// rolled, |vx| × `step`) to the record and writes its summary outputs.
    fn advance(&mut self, values: &mut Values, step: f64) -> Result<(), ModelError> {
        let (Some(record), Some(solver)) = (self.wear.as_mut(), self.solver.as_ref()) else {
            return Ok(());
        };
        let [left, right] = solver.wheelset.wear_rates();
        let rates = [[&left.wheel, &left.rail], [&right.wheel, &right.rail]];
        record.add(rates, values.real(var::vx).abs() * step);
        write_wear_record(values, Some(record))
    }

    /// Writes the wear record to `wearOutput` (when it names a file).
    fn terminate(&mut self, values: &Values) -> Result<(), ModelError> {
        let output = values.string(var::wearOutput);
        let Some(record) = self.wear.as_ref().filter(|_| !output.is_empty()) else {
            return Ok(());
        };
        std::fs::write(output, record.csv()).map_err(|e| {
            ModelError::Error(format!(
                "wearOutput = {output:?}: cannot write the wear record: {e}"
            ))
        })
    }

    /// The outputs at `values` from the warm starts and output slots of the last step, which are
    /// restored afterwards (a patch keeps the slot it has in the last step's outputs).
    fn probe(&mut self, values: &mut Values) -> Result<(), ModelError> {
        let solver = self.solver.as_mut().ok_or_else(not_initialized)?;
        let (warm, slots) = (solver.wheelset.warm_start(), solver.wheelset.slots());
        let solved = solver.solve(values, &mut self.probe_result);
        solver.wheelset.set_warm_start(warm);
        solver.wheelset.set_slots(slots);
        solved.map(|_| ())
    }

    /// Steps scaled to each input's physics: a creepage change of [`CREEPAGE_STEP`] for the
    /// velocities (vx, vy: × V; yawRate: × V / 1 m, the lever of a wheel; omega: × V / r₀) and the
    /// prescribed creepages, [`SPIN_STEP`] for the spin, [`POSE_STEP`] for y, yaw and roll,
    /// [`HEIGHT_STEP`] for z, [`LOAD_STEP`] of the loads; the rails' displacements and velocities
    /// as the wheelset's own, the curvature and a rail's roll rate over [`CURVATURE_LEVER`];
    /// V = max(|vx|, 0.01 m/s).
    fn difference_step(&self, values: &Values, v: &VarInfo) -> f64 {
        let speed = values.real(var::vx).abs().max(V_MIN);
        match RealVar(v.slot) {
            var::y | var::yaw | var::roll => POSE_STEP,
            var::z => HEIGHT_STEP,
            var::trackCurvature => CREEPAGE_STEP / CURVATURE_LEVER,
            var::Qleft | var::Qright => LOAD_STEP * values.reals[v.slot].abs().max(1e3),
            var::vx | var::vy | var::yawRate => CREEPAGE_STEP * speed,
            var::omega => CREEPAGE_STEP * speed / values.real(var::wheelRadius),
            var::xi | var::eta => CREEPAGE_STEP,
            var::phi => SPIN_STEP,
            rail => match RAIL_VARS
                .iter()
                .find_map(|r| r.iter().position(|&x| x == rail))
            {
                // dy, dz, roll, vy, vz, rollRate, as the wheelset's own pose and velocities.
                Some(field) => [
                    POSE_STEP,
                    HEIGHT_STEP,
                    POSE_STEP,
                    CREEPAGE_STEP * speed,
                    CREEPAGE_STEP * speed,
                    CREEPAGE_STEP * speed / CURVATURE_LEVER,
                ][field],
                None => crate::fmi::derivative::default_step(values, v),
            },
        }
    }

    /// The solver's history (the load iteration's warm starts, `wheelset::WarmStart`, and the
    /// patches' output slots, `wheelset::Slot`): a version byte, then per wheel (left, right) a
    /// flag byte (0 none, else 1 + the steps of history) and the approach [m], creep component
    /// [N] and load-balance slope [N/m^1.5], each with its change over the last step and that
    /// change's bend, and the strip ratio as little-endian f64, then per wheel and output slot a presence
    /// byte, the patch's `yRail` [m] as little-endian f64 and its index among the wheel's
    /// patches. Nothing before initialization.
    fn save_state(&self, out: &mut Vec<u8>) {
        if let Some(solver) = &self.solver {
            write_history(solver.wheelset.warm_start(), solver.wheelset.slots(), out);
            if let Some(record) = &self.wear {
                record.save(out);
            }
        }
    }

    fn restore_state(&mut self, bytes: &[u8]) -> Result<(), String> {
        let Some(solver) = &mut self.solver else {
            return if bytes.is_empty() {
                Ok(())
            } else {
                Err(format!(
                    "FMU state holds {} bytes of solver history for an instance that is not \
                     initialized",
                    bytes.len()
                ))
            };
        };
        let (history, wear) = bytes.split_at(bytes.len().min(HISTORY_BYTES));
        let (warm, slots) = parse_history(history)?;
        match self.wear.as_mut() {
            Some(record) => record
                .restore(wear)
                .map_err(|e| format!("FMU state: {e}"))?,
            None if !wear.is_empty() => {
                return Err(format!(
                    "FMU state holds {} bytes of wear record for an instance without a wear model",
                    wear.len()
                ))
            }
            None => {}
        }
        solver.wheelset.set_warm_start(warm);
        solver.wheelset.set_slots(slots);
        Ok(())
    }
}

/// The wear record's summary outputs (`s.wheelWearMass`, `s.railWearMass`, `s.wheelWearDepthMax`,
/// `s.railWearDepthMax`); zero without a record.
fn write_wear_record(values: &mut Values, record: Option<&WearRecord>) -> Result<(), ModelError> {
    use var::*;
    let outputs = [
        [
            left_wheelWearMass,
            left_railWearMass,
            left_wheelWearDepthMax,
            left_railWearDepthMax,
        ],
        [
            right_wheelWearMass,
            right_railWearMass,
            right_wheelWearDepthMax,
            right_railWearDepthMax,
        ],
    ];
    for (side, vars) in outputs.into_iter().enumerate() {
        let s = record.map(|r| r.summary(side)).unwrap_or_default();
        let xs = [
            s.wheel_mass,
            s.rail_mass,
            s.wheel_depth_max,
            s.rail_depth_max,
        ];
        set_outputs(values, vars, xs)?;
    }
    Ok(())
}

fn not_initialized() -> ModelError {
    ModelError::Error("model used before initialization".into())
}

/// Version of the solver-history layout in FMU states (8: warm start with the approach, creep
/// component and load-balance slope, each with its change and bend, the strip ratio, and the
/// output slots of the reported patches, one per contact region).
const HISTORY_VERSION: u8 = 8;
/// Values of one wheel's warm start in the layout ([`warm_fields`]).
const WARM_FIELDS: usize = 10;
/// Bytes of one wheel's warm start: flag (0 none, else 1 + [`WarmStart::history`]), then its
/// values as little-endian f64.
const WARM_SIDE_BYTES: usize = 1 + WARM_FIELDS * 8;
/// Bytes of one output slot: presence flag, `yRail` as little-endian f64, patch index.
const SLOT_BYTES: usize = 1 + 8 + 1;
/// Bytes of the whole history.
const HISTORY_BYTES: usize = 1 + 2 * WARM_SIDE_BYTES + 2 * MAX_PATCHES * SLOT_BYTES;

/// The warm start's values in the state layout's order: approach, creep component and slope,
/// each as value, change, bend; then the strip ratio.
fn warm_fields(w: &WarmStart) -> [f64; WARM_FIELDS] {
    let [a, c, s] = [w.approach, w.creep, w.slope];
    [
        a.value,
        a.step,
        a.bend,
        c.value,
        c.step,
        c.bend,
        s.value,
        s.step,
        s.bend,
        w.strip_ratio,
    ]
}

/// Appends the warm starts and output slots in the layout of [`Model::save_state`].
fn write_history(
    warm: [Option<WarmStart>; 2],
    slots: [[Option<Slot>; MAX_PATCHES]; 2],
    out: &mut Vec<u8>,
) {
    out.push(HISTORY_VERSION);
    for side in warm {
        out.push(side.map_or(0, |w| 1 + w.history.min(2)));
        let w = side.unwrap_or(WarmStart {
            approach: Trend::new(0.0),
            creep: Trend::new(0.0),
            slope: Trend::new(0.0),
            history: 0,
            strip_ratio: 1.0,
        });
        for v in warm_fields(&w) {
            out.extend_from_slice(&v.to_le_bytes());
        }
    }
    for slot in slots.iter().flatten() {
        out.push(u8::from(slot.is_some()));
        let (y_rail, group) = slot.map_or((0.0, 0), |s| (s.y_rail, s.group));
        out.extend_from_slice(&y_rail.to_le_bytes());
        out.push(group as u8);
    }
}

/// Little-endian f64 at byte `i` of `bytes`.
fn f64_at(bytes: &[u8], i: usize) -> f64 {
    let mut b = [0u8; 8];
    b.copy_from_slice(&bytes[i..i + 8]);
    f64::from_le_bytes(b)
}

/// The warm starts and output slots of a history; rejects any other length, version or flag,
/// non-finite values, non-positive approaches and patch indices out of range.
type History = ([Option<WarmStart>; 2], [[Option<Slot>; MAX_PATCHES]; 2]);

/// Reads what [`Model::save_state`] wrote (see [`History`]).
fn parse_history(bytes: &[u8]) -> Result<History, String> {
    if bytes.len() != HISTORY_BYTES || bytes[0] != HISTORY_VERSION {
        return Err(format!(
            "FMU state: solver history of {} bytes, version {:?} (expected {HISTORY_BYTES} \
             bytes, version {HISTORY_VERSION})",
            bytes.len(),
            bytes.first()
        ));
    }
    let mut warm = [None; 2];
    for (side, chunk) in warm
        .iter_mut()
        .zip(bytes[1..1 + 2 * WARM_SIDE_BYTES].chunks_exact(WARM_SIDE_BYTES))
    {
        let values: [f64; WARM_FIELDS] = std::array::from_fn(|k| f64_at(chunk, 1 + 8 * k));
        // The order of `warm_fields`.
        let trend = |k: usize| Trend {
            value: values[k],
            step: values[k + 1],
            bend: values[k + 2],
        };
        let (approach, creep, slope) = (trend(0), trend(3), trend(6));
        let strip_ratio = values[9];
        let positive = |v: f64| v > 0.0 && v.is_finite();
        let valid = positive(approach.value)
            && approach.is_finite()
            && creep.is_finite()
            && slope.is_finite()
            && slope.value >= 0.0
            && positive(strip_ratio);
        *side = match chunk[0] {
            0 => None,
            flag @ 1..=3 if valid => Some(WarmStart {
                approach,
                creep,
                slope,
                history: flag - 1,
                strip_ratio,
            }),
            flag => {
                return Err(format!(
                    "FMU state: invalid warm start (flag {flag}, approach {approach:?} m, creep \
                     component {creep:?} N, slope {slope:?} N/m^1.5, strip ratio {strip_ratio})"
                ))
            }
        };
    }
    let mut slots = [[None; MAX_PATCHES]; 2];
    for (slot, chunk) in slots
        .iter_mut()
        .flatten()
        .zip(bytes[1 + 2 * WARM_SIDE_BYTES..].chunks_exact(SLOT_BYTES))
    {
        let (y_rail, group) = (f64_at(chunk, 1), chunk[9] as usize);
        *slot = match chunk[0] {
            0 => None,
            1 if y_rail.is_finite() && group < MAX_GROUPS => Some(Slot { y_rail, group }),
            flag => {
                return Err(format!(
                    "FMU state: invalid output slot (flag {flag}, yRail {y_rail} m, patch {group})"
                ))
            }
        };
    }
    Ok((warm, slots))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn relative_profile_names_are_looked_up_in_the_resources_first() {
        let benchmark =
            Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/profiles/MBench_S1002_v3.prw");
        let resources = std::env::temp_dir().join(format!("wrc-resources-{}", std::process::id()));
        std::fs::create_dir_all(&resources).unwrap();
        std::fs::copy(&benchmark, resources.join("MBench_S1002_v3.prw"))
            .unwrap_or_else(|e| panic!("{}: {e}", benchmark.display()));
        let wheel = ProfileKind::Wheel;
        let bundled = load_profile("MBench_S1002_v3.prw", wheel, 1e-3, Some(&resources)).unwrap();
        let direct = Profile::from_file(&benchmark, Some(wheel), 1e-3).unwrap();
        assert_eq!(bundled.points(), direct.points());
        // Built-in names stay built-in.
        assert_eq!(
            load_profile("s1002", wheel, 0.0, Some(&resources))
                .unwrap()
                .name(),
            "S1002"
        );

        let Err(ModelError::Error(e)) = load_profile("other.prw", wheel, 0.0, Some(&resources))
        else {
            panic!("a missing file must fail")
        };
        let cwd = std::env::current_dir().unwrap();
        for text in [
            "wheelProfile = \"other.prw\": ".to_string(),
            "unknown built-in profile \"other.prw\"".to_string(),
            format!(
                "looked in the FMU's resources folder ({})",
                resources.join("other.prw").display()
            ),
            format!(
                " and the working directory ({})",
                cwd.join("other.prw").display()
            ),
        ] {
            assert!(e.contains(&text), "{text:?} not in {e:?}");
        }
        let Err(ModelError::Error(e)) = load_profile("other.prr", ProfileKind::Rail, 0.0, None)
        else {
            panic!("a missing file must fail")
        };
        assert!(e.starts_with("railProfile = \"other.prr\": "), "{e}");
        assert!(e.contains("there is no resources folder"), "{e}");
        let _ = std::fs::remove_dir_all(&resources);
    }

    fn bytes_of(warm: [Option<WarmStart>; 2], slots: [[Option<Slot>; MAX_PATCHES]; 2]) -> Vec<u8> {
        let mut out = Vec::new();
        write_history(warm, slots, &mut out);
        out
    }

    #[test]
    fn history_bytes_round_trip_and_corruption_is_rejected() {
        let warm = [
            None,
            Some(WarmStart {
                approach: Trend {
                    value: 8.1e-5,
                    step: -2.5e-8,
                    bend: 1.5e-10,
                },
                creep: Trend {
                    value: -123.25,
                    step: 0.75,
                    bend: -0.125,
                },
                slope: Trend {
                    value: 3.5e15,
                    step: 2.0e12,
                    bend: -1.0e9,
                },
                history: 2,
                strip_ratio: 1.25,
            }),
        ];
        let mut slots = [[None; MAX_PATCHES]; 2];
        slots[1][0] = Some(Slot {
            y_rail: -0.0123,
            group: 2,
        });
        slots[1][2] = Some(Slot {
            y_rail: -0.0351,
            group: 0,
        });
        let bytes = bytes_of(warm, slots);
        assert_eq!(parse_history(&bytes), Ok((warm, slots)));
        // Wrong length, version, flag; a non-positive or non-finite approach or strip ratio; a
        // NaN creep or change; a slot's patch index out of range or a non-finite yRail.
        assert!(parse_history(&bytes[..bytes.len() - 1]).is_err());
        let mut v = bytes.clone();
        v[0] = 4;
        assert!(parse_history(&v).is_err());
        let mut v = bytes.clone();
        v[1] = 7;
        assert!(parse_history(&v).is_err());
        // A NaN bend (the right wheel's approach bend, field 2 of its warm start).
        let bend = 1 + WARM_SIDE_BYTES + 1 + 8 * 2;
        let mut v = bytes.clone();
        v[bend..bend + 8].copy_from_slice(&f64::NAN.to_le_bytes());
        assert!(parse_history(&v).is_err());
        let slot_start = 1 + 2 * WARM_SIDE_BYTES + MAX_PATCHES * SLOT_BYTES;
        let mut v = bytes.clone();
        v[slot_start + 9] = MAX_GROUPS as u8;
        assert!(parse_history(&v).is_err());
        let mut v = bytes.clone();
        v[slot_start + 1..slot_start + 9].copy_from_slice(&f64::NAN.to_le_bytes());
        assert!(parse_history(&v).is_err());
        for (approach, creep, creep_step, strip_ratio) in [
            (0.0, 0.0, 0.0, 1.0),
            (-1e-5, 0.0, 0.0, 1.0),
            (f64::INFINITY, 0.0, 0.0, 1.0),
            (1e-5, f64::NAN, 0.0, 1.0),
            (1e-5, 0.0, f64::INFINITY, 1.0),
            (1e-5, 0.0, 0.0, 0.0),
            (1e-5, 0.0, 0.0, f64::NAN),
            (1e-5, 0.0, 0.0, -1.0),
        ] {
            let w = WarmStart {
                approach: Trend::new(approach),
                creep: Trend {
                    step: creep_step,
                    ..Trend::new(creep)
                },
                slope: Trend::new(0.0),
                history: 1,
                strip_ratio,
            };
            let v = bytes_of([Some(w), None], slots);
            assert!(parse_history(&v).is_err(), "{w:?}");
        }
        // A negative or non-finite slope.
        for slope in [-1.0, f64::NAN, f64::INFINITY] {
            let mut w = warm[1].expect("the right wheel's warm start");
            w.slope.value = slope;
            let v = bytes_of([Some(w), None], slots);
            assert!(parse_history(&v).is_err(), "{w:?}");
        }
    }
}
