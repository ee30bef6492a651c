//! `gsph materials`: the material library ([`crate::scene::library`]).

use crate::scene;
use std::path::PathBuf;

/// Arguments of `gsph materials`.
#[derive(clap::Args, Debug)]
pub struct MaterialsArgs {
    /// A library material to print.
    #[arg(conflicts_with = "scene")]
    pub name: Option<String>,
    /// Print the resolved materials of this scene instead.
    #[arg(long)]
    pub scene: Option<PathBuf>,
    /// Override a scene key (dotted path; with --scene).
    #[arg(long = "set", value_name = "KEY=VALUE", requires = "scene")]
    pub set: Vec<String>,
    /// Remove a scene key (dotted path; with --scene).
    #[arg(long = "unset", value_name = "KEY", requires = "scene")]
    pub unset: Vec<String>,
}

/// Runs `gsph materials`.
pub fn command(args: MaterialsArgs) -> Result<(), String> {
    let MaterialsArgs {
        name,
        scene: path,
        set,
        unset,
    } = args;
    use crate::scene::library;
    let text = match (name, path) {
        (Some(name), _) => library::show(&name)?,
        (None, Some(path)) => library::scene_report(&path, &scene::with_unsets(set, &unset))?,
        (None, None) => library::list()?,
    };
    out!("{}", text.trim_end());
    Ok(())
}
