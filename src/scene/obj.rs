//! Wavefront OBJ loading for `gr.mesh(name, file)` and `readobj`.
