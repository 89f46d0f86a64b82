//! Image files: PNG/EXR written atomically, read back for diffs.
