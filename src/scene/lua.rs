//! The `gr` Lua module (see shared/design/scene-language.md).
