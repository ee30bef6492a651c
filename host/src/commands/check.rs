//! `gsph check`: a scene validated and set up as a run would be, without running it.

use crate::reference::Reference;
use crate::scene::{self, build_particles, scene_name};
use crate::sim::{Sim, SimError};
use std::path::PathBuf;

/// Arguments of `gsph check`.
#[derive(clap::Args, Debug)]
pub struct CheckArgs {
    /// Scene file.
    pub scene: PathBuf,
    /// Scene overrides.
    #[command(flatten)]
    pub overrides: super::Overrides,
}

/// Sets the scene up as a run would (neighbour lists, overlap check, specialisation), so
/// `gsph check` fails where `gsph run` would fail before its first step.
fn probe(sc: &scene::Scene, parts: &scene::InitialParticles) -> Result<(), SimError> {
    match sc.dim {
        1 => Sim::<1>::new(sc, parts).map(drop),
        2 => Sim::<2>::new(sc, parts).map(drop),
        _ => Sim::<3>::new(sc, parts).map(drop),
    }
}

/// Runs `gsph check`: prints the scene's particles, materials, effects and specialisation.
pub fn command(args: CheckArgs) -> Result<(), String> {
    let CheckArgs {
        scene: path,
        overrides,
    } = args;
    let set = overrides.list();
    let sc = scene::load(&path, &set).map_err(|e| e.to_string())?;
    let at = |e: &dyn std::fmt::Display| format!("{}: {e}", path.display());
    let parts = build_particles(&sc).map_err(|e| at(&e))?;
    Reference::from_scene(&sc, &parts.x, &parts.spacing).map_err(|e| at(&e))?;
    probe(&sc, &parts).map_err(|e| at(&e))?;
    let materials: Vec<_> = sc
        .materials
        .iter()
        .map(crate::scene::materials::material_of)
        .collect();
    let effects = crate::sim::resolve_effects(&sc, &materials);
    out!("scene     {}", scene_name(&sc, &path));
    out!("dim       {}", sc.dim);
    out!("scheme    {}", sc.scheme);
    // where each material came from: the scene, the library or an included file
    for (k, m) in sc.materials.iter().enumerate() {
        let source = sc.material_sources.get(k).map_or("scene", String::as_str);
        out!("material  {}: {source}", m.name);
    }
    out!("particles {}", parts.len());
    for (b, body) in sc.bodies.iter().enumerate() {
        let n = parts.body.iter().filter(|&&k| k as usize == b).count();
        match &body.pores {
            Some(pores) => out!(
                "  body {b} ({}): {n}, porosity m = {:.4} as built ({:.4} from the pore geometry)",
                body.material,
                parts.porosity[b],
                crate::scene::pores::geometric_porosity(pores)
            ),
            None => out!("  body {b} ({}): {n}", body.material),
        }
    }
    out!("effects   {effects}");
    if sc.options.riemann == Some(gsph_core::schemes::RiemannSolver::TwoShock) {
        // the two-shock solver's Us = c + s up slope of each material
        let slopes: Vec<String> = sc
            .materials
            .iter()
            .zip(&materials)
            .map(|(spec, m)| {
                let how = match m.eos {
                    gsph_core::material::Eos::MieGruneisen(_)
                    | gsph_core::material::Eos::Hugoniot(_)
                    | gsph_core::material::Eos::TwoCurve(_) => "the EOS's",
                    _ => "weak-shock (1 + K')/4",
                };
                format!("{} {:.4} ({how})", spec.name, m.eos.hugoniot_slope())
            })
            .collect();
        out!(
            "riemann   two_shock, Hugoniot slope s: {}",
            slopes.join(", ")
        );
    }
    let dim = sc.dim;
    let scheme = sc.scheme;
    let (n, all) = crate::specs::compiled();
    match crate::specs::find(dim, scheme.family(), effects) {
        Some(s) if s.compiled => {
            out!(
                "kernel    {} (compiled; this build contains {n} of {all} specialisations)",
                s.name
            );
            // what crosses rank boundaries under MPI (docs/mpi.md)
            let halo: Vec<String> = scheme
                .family()
                .exchanges()
                .iter()
                .filter(|x| x.applies(effects))
                .map(|x| {
                    let f: Vec<&str> = x.fields.names().collect();
                    format!("{} ({})", x.before, f.join(" "))
                })
                .collect();
            out!(
                "halo      under MPI, ghosts refreshed before: {}",
                halo.join(", ")
            );
        }
        Some(_) => {
            return Err(at(&SimError::NotCompiled {
                dim,
                scheme,
                effects,
            }))
        }
        None => {
            return Err(format!(
                "no specialisation exists for {dim}D {} with effects {effects}",
                sc.scheme
            ))
        }
    }
    Ok(())
}
