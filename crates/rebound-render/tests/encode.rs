//! PNG and GIF files read back with the same crates' decoders.

use std::sync::Arc;

use rebound::ColliderShape;
use rebound::prelude::{Pose, Vec3};
use rebound_render::{
    Camera, GifWriter, Mesh, RenderError, RenderOptions, RenderScene, Rgba, render,
};

fn picture(x: f32) -> rebound_render::Image {
    let mut scene = RenderScene::new();
    let ball = Mesh::from_shape(&ColliderShape::Ball { radius: 1.0 }, 12).expect("valid");
    scene.push(
        Arc::new(ball),
        Pose {
            position: Vec3::new(x, 1.0, 0.0),
            ..Pose::IDENTITY
        },
        Rgba::RED,
    );
    let camera = Camera {
        width: 80,
        height: 60,
        ..Camera::default()
    };
    render(&scene, &camera, &RenderOptions::default()).expect("renders")
}

#[test]
fn a_png_reads_back_to_the_same_pixels() {
    let image = picture(0.0);
    let bytes = image.to_png().expect("encodes");
    let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    let mut reader = decoder.read_info().expect("a PNG");
    let mut data = vec![0; reader.output_buffer_size().expect("size")];
    let info = reader.next_frame(&mut data).expect("one frame");
    assert_eq!((info.width, info.height), (80, 60));
    assert_eq!(info.color_type, png::ColorType::Rgba);
    assert_eq!(&data[..info.buffer_size()], image.rgba());
}

#[test]
fn a_gif_holds_every_frame_at_the_stated_delay_and_refuses_a_wrong_size() {
    let mut gif = GifWriter::new(Vec::new(), 80, 60, 1.0 / 30.0).expect("starts");
    for i in 0..3 {
        gif.add_frame(&picture(i as f32)).expect("adds");
    }
    let small = Camera {
        width: 40,
        height: 30,
        ..Camera::default()
    };
    let wrong = render(&RenderScene::new(), &small, &RenderOptions::default()).expect("renders");
    assert!(matches!(
        gif.add_frame(&wrong),
        Err(RenderError::FrameSize { width: 40, .. })
    ));
    assert_eq!(gif.frame_count(), 3);
    let bytes = gif.finish().expect("finishes");
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::RGBA);
    let mut decoder = options
        .read_info(std::io::Cursor::new(bytes))
        .expect("a GIF");
    assert_eq!((decoder.width(), decoder.height()), (80, 60));
    // Each frame holds the changed pixels; transparent ones show the frame before (disposal "keep").
    let mut shown = vec![0u8; 80 * 60 * 4];
    let mut frames = 0;
    while let Some(frame) = decoder.read_next_frame().expect("decodes") {
        // 1/30 s is 3.33 cs, written as 3.
        assert_eq!(frame.delay, 3);
        assert_eq!(frame.dispose, gif::DisposalMethod::Keep);
        assert_eq!(
            (frame.left, frame.top, frame.width, frame.height),
            (0, 0, 80, 60)
        );
        for (out, new) in shown.chunks_exact_mut(4).zip(frame.buffer.chunks_exact(4)) {
            if new[3] != 0 {
                out.copy_from_slice(new);
            }
        }
        // Quantised to 256 colours: each channel within a few levels of the picture.
        let expected = picture(frames as f32);
        let worst = shown
            .iter()
            .zip(expected.rgba())
            .map(|(a, b)| a.abs_diff(*b))
            .max();
        assert!(
            worst.is_some_and(|w| w <= 24),
            "frame {frames}: worst channel error {worst:?}"
        );
        frames += 1;
    }
    assert_eq!(frames, 3);
}

#[test]
fn a_bad_gif_size_or_interval_is_refused() {
    for (width, interval, name) in [
        (0, 0.1, "width"),
        (70_000, 0.1, "width"),
        (10, 0.0, "frame_interval"),
    ] {
        match GifWriter::new(Vec::new(), width, 10, interval) {
            Err(RenderError::Options { field, .. }) => assert_eq!(field, name),
            other => panic!("{name}: {other:?}"),
        }
    }
}
