//! Where a relative path a scene names (a mesh, texture, bump map, module) is looked for:
//! beside the scene, then, when the scene lies inside the folder glint was started in (the
//! course ran `./A4 Assets/scene.lua` from the assignment folder, and its scenes name
//! `'Assets/cow.obj'`), relative to that folder, which such a scene may then read. A file
//! found in neither names both paths tried, and a case-only near miss (`eevee.obj` for
//! `Eevee.obj`, which worked on the author's macOS disk) is offered.

use super::files::{Opened, ReadPolicy};
use crate::folder_walk::{self, FileId};
use std::path::{Component, Path, PathBuf};

/// The folders relative paths resolve against.
#[derive(Clone, Debug)]
pub struct SceneFolders {
    /// The scene's folder (as given: relative to the current folder, or absolute).
    pub scene: PathBuf,
    /// The folder glint was started in, when the scene lies inside it (else None).
    pub start: Option<PathBuf>,
}

impl SceneFolders {
    /// The folders of a scene in `scene_dir`, glint having been started in the current
    /// folder.
    pub fn new(scene_dir: &Path) -> SceneFolders {
        let scene_dir = if scene_dir.as_os_str().is_empty() {
            Path::new(".")
        } else {
            scene_dir
        };
        let home = std::env::var_os("HOME").map(PathBuf::from);
        let start = std::env::current_dir()
            .ok()
            .filter(|_| start_counts(Path::new("."), scene_dir, home.as_deref()));
        SceneFolders {
            scene: scene_dir.to_path_buf(),
            start,
        }
    }

    /// The folders besides the scene's own that the scene may read (the start folder).
    pub fn readable(&self) -> Vec<PathBuf> {
        self.start.iter().cloned().collect()
    }

    /// The file `written` (as the scene wrote it) names, opened (see
    /// [`ReadPolicy::open`]), or why it cannot be read (`what`: "mesh file", "texture", …).
    pub fn find(&self, policy: &ReadPolicy, written: &str, what: &str) -> Result<Opened, String> {
        let rel = Path::new(written);
        let mut tried = vec![(self.scene.join(rel), self.scene.clone())];
        if let Some(start) = &self.start {
            if !rel.is_absolute() {
                tried.push((start.join(rel), start.clone()));
            }
        }
        let allowed: Vec<&(PathBuf, PathBuf)> =
            tried.iter().filter(|(p, _)| policy.allows(p)).collect();
        let Some(first) = allowed.first() else {
            // Outside every readable folder: refused as such, whether or not it exists.
            return policy.open(&tried[0].0, what);
        };
        for (path, _) in &allowed {
            if policy.present(path) {
                return policy.open(path, what);
            }
        }
        let near = allowed
            .iter()
            .find_map(|(_, base)| case_near_miss(policy, base, rel))
            .map(|p| format!("; did you mean '{}'?", crate::display_path::shown(&p)))
            .unwrap_or_default();
        if allowed.len() == 1 {
            let error = policy.open(&first.0, what).err().unwrap_or_default();
            return Err(error + &near);
        }
        Err(format!(
            "cannot read {what} '{written}': no such file beside the scene ('{}') nor from the folder glint was started in ('{}'){near}",
            crate::display_path::shown(&allowed[0].0),
            crate::display_path::shown(&allowed[1].0)
        ))
    }
}

/// Whether the start folder `start` counts as a second folder for a scene in `scene`:
/// only when the scene lies below it, and never when it is the filesystem's root or the
/// home folder `home` (a scene anywhere below those would gain the whole disk or every
/// file of the user; the course's layout is an assignment folder). Judged by the
/// folders' identities, not their absolute paths (which may be past PATH_MAX).
fn start_counts(start: &Path, scene: &Path, home: Option<&Path>) -> bool {
    let id = |p: &Path| FileId::of_folder(p).ok();
    let (Ok(scene_fd), Some(start_id)) = (folder_walk::open_folder(scene), id(start)) else {
        return false;
    };
    let too_wide = Some(start_id) == id(Path::new("/")) || Some(start_id) == home.and_then(id);
    !too_wide
        && FileId::of_fd(&scene_fd).is_ok_and(|scene_id| scene_id != start_id)
        && folder_walk::lies_within(&scene_fd, &[start_id])
}

/// `rel` under `base` with each component that does not exist replaced by the one entry
/// of its folder that differs from it in case only, if that finds a file (None
/// otherwise, or when nothing differed). Only folders the scene may read are listed.
fn case_near_miss(policy: &ReadPolicy, base: &Path, rel: &Path) -> Option<PathBuf> {
    let mut dir = base.to_path_buf();
    let mut out = PathBuf::new();
    let mut changed = false;
    for component in rel.components() {
        let Component::Normal(name) = component else {
            out.push(component);
            dir.push(component);
            continue;
        };
        if std::fs::symlink_metadata(dir.join(name)).is_ok() {
            out.push(name);
            dir.push(name);
            continue;
        }
        if !policy.allows(&dir) {
            return None;
        }
        let wanted = name.to_string_lossy().to_lowercase();
        let mut matches = std::fs::read_dir(&dir)
            .ok()?
            .filter_map(Result::ok)
            .map(|e| e.file_name())
            .filter(|n| n.to_string_lossy().to_lowercase() == wanted);
        let found = matches.next()?;
        if matches.next().is_some() {
            return None;
        }
        out.push(&found);
        dir.push(&found);
        changed = true;
    }
    changed.then_some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_start_folder_counts_only_above_the_scene_and_never_root_or_home() {
        let (_dir, me) = crate::testing::scratch::temp_file("paths-start", "h/me");
        let (a4, assets, other) = (me.join("a4"), me.join("a4/Assets"), me.join("other"));
        std::fs::create_dir_all(&assets).unwrap();
        std::fs::create_dir_all(&other).unwrap();
        let home = Some(me.as_path());
        assert!(start_counts(&a4, &assets, home));
        assert!(!start_counts(&a4, &a4, home), "the scene's own folder");
        assert!(!start_counts(&a4, &other, home));
        assert!(!start_counts(&me, &assets, home), "home");
        assert!(!start_counts(Path::new("/"), &assets, home), "root");
    }

    #[test]
    fn a_case_only_near_miss_is_found_component_by_component() {
        let dir = crate::testing::scratch::temp_dir("paths-case");
        std::fs::create_dir_all(dir.as_path().join("Assets")).unwrap();
        std::fs::write(dir.as_path().join("Assets/Eevee.obj"), b"v 0 0 0\n").unwrap();
        let policy = ReadPolicy::new(dir.as_path(), &[]);
        assert_eq!(
            case_near_miss(&policy, dir.as_path(), Path::new("assets/eevee.OBJ")),
            Some(PathBuf::from("Assets/Eevee.obj"))
        );
        assert_eq!(
            case_near_miss(&policy, dir.as_path(), Path::new("Assets/Eevee.obj")),
            None
        );
        assert_eq!(
            case_near_miss(&policy, dir.as_path(), Path::new("Assets/cow.obj")),
            None
        );
    }
}
