//! EXR tiles: the tile's linear f32 RGB pixels, exactly the full render's floats there,
//! with the tile's record (the text pairs the tile writer gives) as text attributes of
//! its layer. The PNG tiles' twin for `.exr` outputs.

use crate::film::Film;
use exr::meta::attribute::{AttributeValue, Text};
use exr::prelude::LayerAttributes;
use std::collections::HashMap;
use std::path::Path;

/// Writes `film` with the text attributes `record` into `file` (a fresh temporary file,
/// which the caller syncs).
pub fn write_exr(
    film: &Film,
    record: &[(&str, String)],
    file: &mut std::fs::File,
) -> Result<(), String> {
    let mut attributes = LayerAttributes::named("glint tile");
    for (key, value) in record {
        attributes.other.insert(
            Text::from(*key),
            AttributeValue::Text(Text::from(value.as_str())),
        );
    }
    use std::io::Write;
    let mut out = std::io::BufWriter::new(file);
    crate::image_io::write_exr_layer(film, attributes, &mut out).map_err(|e| e.to_string())?;
    out.flush().map_err(|e| e.to_string())
}

/// An EXR layer's text attributes (key to text).
pub type Texts = HashMap<String, String>;

/// The text attributes of the first layer and its size, without reading the pixels.
pub fn read_exr_record(path: &Path) -> Result<(Texts, (u32, u32)), String> {
    let meta = exr::meta::MetaData::read_from_file(path, false).map_err(|e| e.to_string())?;
    let header = meta.headers.first().ok_or("it has no layer")?;
    let size = (header.layer_size.x() as u32, header.layer_size.y() as u32);
    Ok((texts(&header.own_attributes), size))
}

fn texts(attributes: &LayerAttributes) -> Texts {
    attributes
        .other
        .iter()
        .filter_map(|(k, v)| match v {
            AttributeValue::Text(t) => Some((k.to_string(), t.to_string())),
            _ => None,
        })
        .collect()
}

/// The first RGB(A) layer's pixels as a linear film (alpha dropped).
pub fn read_exr_film(path: &Path) -> Result<Film, String> {
    let image = exr::prelude::read_first_rgba_layer_from_file(
        path,
        |size, _| Film::new(size.width() as u32, size.height() as u32),
        |film: &mut Film, p, (r, g, b, _a): (f32, f32, f32, f32)| {
            film.set(p.x() as u32, p.y() as u32, [r, g, b])
        },
    )
    .map_err(|e| e.to_string())?;
    Ok(image.layer_data.channel_data.pixels)
}
