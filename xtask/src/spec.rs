//! Figure specs, `data/figures/figN.toml`: a base scene in tack-cli's scene format (`[scene]`,
//! `version = 1`) and the figure's sweep over it in two parameter sets, `[quick]` and `[full]`.
//!
//! Each parameter set may hold `set = ["key.path=value", ...]`: tack-cli `--set` overrides of
//! the base scene for that mode; the other keys are the figure's own sweep parameters (checked
//! by the figure, unknown keys rejected). A spec without `[scene]` names the spec whose scene
//! and runs it reuses in `uses = "figK.toml"`.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use serde::Deserialize;
use serde::de::DeserializeOwned;
use tack::Scene;
use tack::scene::SceneSchema;

/// The top level of a spec file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SpecFile {
    figure: u8,
    title: String,
    #[serde(default)]
    uses: Option<String>,
    #[serde(default)]
    scene: Option<toml::Table>,
    quick: toml::Table,
    full: toml::Table,
}

/// One figure's spec in one mode.
#[derive(Debug, Clone)]
pub struct FigureSpec {
    /// Figure number (1–8).
    pub figure: u8,
    /// What the figure shows.
    pub title: String,
    /// Full mode (the paper's settings) rather than quick mode.
    pub full: bool,
    /// The spec file.
    pub path: PathBuf,
    /// The spec file's text (recorded in the figure's result file).
    pub text: String,
    base: Option<Scene>,
    params: toml::Table,
}

impl FigureSpec {
    /// Loads `dir/figN.toml` in quick or full mode.
    pub fn load(dir: &Path, figure: u8, full: bool) -> Result<Self> {
        let path = dir.join(format!("fig{figure}.toml"));
        let text = std::fs::read_to_string(&path)
            .with_context(|| format!("reading the figure spec {}", path.display()))?;
        let file: SpecFile =
            toml::from_str(&text).with_context(|| format!("figure spec {}", path.display()))?;
        if file.figure != figure {
            bail!(
                "{}: figure = {} but the file is for figure {figure}",
                path.display(),
                file.figure
            );
        }
        let mut params = if full { file.full } else { file.quick };
        let set: Vec<String> = match params.remove("set") {
            Some(v) => v.try_into().with_context(|| {
                format!(
                    "{}: `set` must be a list of \"key=value\" strings",
                    path.display()
                )
            })?,
            None => Vec::new(),
        };
        let base = match file.scene {
            Some(scene) => Some(
                Scene::parse(&toml::to_string(&scene)?, dir, &set)
                    .with_context(|| format!("{}: [scene]", path.display()))?,
            ),
            None if !set.is_empty() => bail!("{}: `set` needs a [scene]", path.display()),
            None => None,
        };
        if base.is_none() && file.uses.is_none() {
            bail!(
                "{}: give a [scene] or `uses = \"figK.toml\"`",
                path.display()
            );
        }
        Ok(Self {
            figure,
            title: file.title,
            full,
            path,
            text,
            base,
            params,
        })
    }

    /// The mode's sweep parameters as the figure's typed struct.
    pub fn params<T: DeserializeOwned>(&self) -> Result<T> {
        let mode = if self.full { "full" } else { "quick" };
        self.params
            .clone()
            .try_into()
            .with_context(|| format!("{}: [{mode}]", self.path.display()))
    }

    /// The base scene with the mode's overrides.
    pub fn scene(&self) -> Result<SceneSchema> {
        match &self.base {
            Some(s) => Ok(s.file.clone()),
            None => bail!("{}: has no [scene]", self.path.display()),
        }
    }

    /// Directory of the spec (relative scene paths resolve against it).
    pub fn dir(&self) -> &Path {
        self.path.parent().unwrap_or(Path::new("."))
    }
}

/// A scene built in code from a (modified) base scene.
pub fn scene(file: SceneSchema, dir: &Path) -> Result<Scene> {
    Ok(Scene::from_file(file, dir)?)
}
