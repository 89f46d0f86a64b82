//! SceneGraph → world-space Scene (filled in by the flatten step).
