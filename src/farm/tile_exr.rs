//! EXR tiles: the tile's linear f32 RGB pixels, exactly the full render's floats there,
//! with the tile's record (the text pairs the tile writer gives) as text attributes of
//! its layer. The PNG tiles' twin for `.exr` outputs.

use crate::film::Film;
use crate::scene::lua::MAX_IMAGE_SIDE;
use exr::meta::attribute::{AttributeValue, Text};
use exr::prelude::LayerAttributes;
use std::collections::HashMap;
use std::io::Cursor;

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

/// The text attributes and the size of an EXR tile's layer, from the file's bytes. The
/// header is checked first by [`crate::image_check::exr_window`] (one part, no deep
/// data, no tiny tiles) and its data window held to `max_pixels` and glint's largest
/// side, before the exr crate reads anything it would size from them.
pub fn read_exr_record(bytes: &[u8], max_pixels: u64) -> Result<(Texts, (u32, u32)), String> {
    let (w, h) = crate::image_check::exr_window(bytes)?;
    // The side bounds the decoder's table of chunks (one per line or block).
    let side = u64::from(MAX_IMAGE_SIDE);
    if w * h > max_pixels || w > side || h > side {
        return Err(format!(
            "its data window is {w}×{h} pixels, over the limit of {max_pixels} (each side at most {side})"
        ));
    }
    let meta = exr::meta::MetaData::read_from_buffered(Cursor::new(bytes), false)
        .map_err(|e| e.to_string())?;
    let [header] = &meta.headers[..] else {
        return Err("it has several parts; a tile has one".into());
    };
    let size = (header.layer_size.x() as u32, header.layer_size.y() as u32);
    if (u64::from(size.0), u64::from(size.1)) != (w, h) {
        return Err(format!(
            "its layer is {}×{}, its data window {w}×{h}",
            size.0, size.1
        ));
    }
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

/// The RGB pixels of the EXR in `bytes` as a linear film (other channels ignored), from
/// the one layer [`read_exr_record`] checked.
pub fn read_exr_film(bytes: &[u8]) -> Result<Film, String> {
    use exr::prelude::{ReadChannels, ReadLayers};
    let image = exr::prelude::read()
        .no_deep_data()
        .largest_resolution_level()
        .rgb_channels(
            |size, _| Film::new(size.width() as u32, size.height() as u32),
            |film: &mut Film, p, (r, g, b): (f32, f32, f32)| {
                film.set(p.x() as u32, p.y() as u32, [r, g, b])
            },
        )
        .first_valid_layer()
        .all_attributes()
        .from_buffered(Cursor::new(bytes))
        .map_err(|e| e.to_string())?;
    Ok(image.layer_data.channel_data.pixels)
}
