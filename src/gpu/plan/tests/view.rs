//! `glint view`'s frames through the wavefront kernels.

use super::*;

/// `glint view`'s frame s of a band through the wavefront kernels: the camera pass
/// over the band's pixels (one sample each), every generation's five passes, then the
/// store over the same samples; every pass carries the frame's stratum.
#[test]
fn a_view_frame_samples_one_stratum_a_pixel_then_stores() {
    let shape = wavefront_shape(3, 4, Some(3), false);
    let band = bands(PixelRect::full(37, 5), 5, 1)[0];
    let d = view_wavefront_dispatches(band, shape, 7, 2, LAVAPIPE);
    assert_eq!(d.len(), 2 + 5 * shape.generations as usize);
    let entries: Vec<usize> = d.iter().map(|d| d.entry).collect();
    let mut expected = vec![0];
    for _ in 0..shape.generations {
        expected.extend([1, 2, 3, 4, 5]);
    }
    expected.push(6);
    assert_eq!(entries, expected);
    assert_eq!(Entry::WAVEFRONT_VIEW[6], Entry::WavefrontViewStore);
    assert!(d
        .iter()
        .all(|d| d.params.stratum == 7 && d.params.items == 37 * 5));
    assert_eq!(
        d[4].workgroups,
        Workgroups::Indirect(12),
        "generation 0's shadows"
    );
    assert_eq!(
        d[6].workgroups,
        Workgroups::Indirect(0),
        "generation 1's paths"
    );
    let (camera, store) = (d[0], d[d.len() - 1]);
    assert_eq!(camera.workgroups, Workgroups::Direct(3, 1));
    assert_eq!(
        (store.workgroups, store.params),
        (camera.workgroups, camera.params)
    );
    assert!(camera.clears_work && !store.clears_work);
}

/// A view frame of a tree: the camera pass of the frame's stratum, a tree's
/// generations with their rounds, the fold over the band's samples, then the store
/// (entries of `Entry::WAVEFRONT_VIEW_TREE`), every pass told the stratum.
#[test]
fn a_view_frame_of_a_tree_folds_then_stores() {
    let shape = wavefront_shape(3, 4, None, true);
    let band = bands(PixelRect::full(37, 5), 5, 1)[0];
    let d = view_wavefront_dispatches(band, shape, 2, 2, LAVAPIPE);
    let per_generation = TREE_GENERATION_DISPATCHES;
    assert_eq!(d.len(), 3 + per_generation * shape.generations as usize);
    let names: Vec<Entry> = d
        .iter()
        .map(|d| Entry::WAVEFRONT_VIEW_TREE[d.entry])
        .collect();
    assert_eq!(names[..5], Entry::WAVEFRONT_VIEW_TREE[..5]);
    assert_eq!(names[names.len() - 2], Entry::WavefrontFold);
    assert_eq!(names[names.len() - 1], Entry::WavefrontViewStore);
    assert!(d
        .iter()
        .all(|d| d.params.stratum == 2 && d.params.items == 37 * 5));
    let (camera, fold, store) = (d[0], d[d.len() - 2], d[d.len() - 1]);
    assert_eq!(fold.workgroups, camera.workgroups);
    assert_eq!(
        (store.workgroups, store.params),
        (camera.workgroups, camera.params)
    );
    assert!(camera.clears_work && !store.clears_work);
}
