//! Frames written as an animated GIF or as PNG files decode back with the right count, size and
//! content (PNG exactly; GIF within its 256-colour palette), at the frame rate asked; bad
//! sequences and rates are refused by name.

// In tests and benches a failed unwrap is a failed run, with its location.
#![allow(clippy::unwrap_used)]

mod common;

use std::fs::File;

use common::*;
use hyq_render::{
    Frame, GifWriter, PngSequence, WriteError, gif_delay_cs, write_gif, write_png,
    write_png_sequence,
};

/// A few frames of the robot walking 0.2 m per frame, with the camera fixed so that they differ.
fn frames(n: usize) -> Vec<Frame> {
    let mut r = renderer();
    let target = standing_at(0.0, 0.0).0.translation.vector.into();
    (0..n)
        .map(|i| render_standing(&mut r, 0.2 * i as f64, 0.0, Some(target)))
        .collect()
}

fn decode_png(path: &std::path::Path) -> (u32, u32, Vec<u8>) {
    let decoder = png::Decoder::new(std::io::BufReader::new(File::open(path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgb);
    assert_eq!(info.bit_depth, png::BitDepth::Eight);
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

#[test]
fn gif_has_every_frame_at_the_right_size_and_rate() {
    let dir = scratch_dir("gif");
    let path = dir.join("episode.gif");
    let frames = frames(5);
    write_gif(&path, &frames, 10.0).unwrap();

    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::RGBA);
    let mut decoder = options.read_info(File::open(&path).unwrap()).unwrap();
    assert_eq!((decoder.width(), decoder.height()), (480, 360));
    assert_eq!(decoder.repeat(), gif::Repeat::Infinite);
    let mut count = 0;
    while let Some(frame) = decoder.read_next_frame().unwrap() {
        assert_eq!((frame.width, frame.height), (480, 360));
        assert_eq!(
            frame.delay, 10,
            "10 fps is 10 hundredths of a second per frame"
        );
        // The palette keeps the picture: mean error below 6 levels per channel.
        let original = &frames[count].rgb;
        let err: u64 = frame
            .buffer
            .chunks_exact(4)
            .zip(original.chunks_exact(3))
            .map(|(g, o)| (0..3).map(|c| u64::from(g[c].abs_diff(o[c]))).sum::<u64>())
            .sum();
        let mean = err as f64 / original.len() as f64;
        assert!(mean < 6.0, "frame {count}: mean error {mean:.2}");
        count += 1;
    }
    assert_eq!(count, 5);
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn streaming_gif_writer_counts_frames_and_refuses_another_size() {
    let dir = scratch_dir("gif-stream");
    let frames = frames(2);
    let mut gif = GifWriter::create(dir.join("a.gif"), 480, 360, 30.0).unwrap();
    assert_eq!(gif.delay_cs(), 3);
    gif.push(&frames[0]).unwrap();
    gif.push(&frames[1]).unwrap();
    let err = gif.push(&Frame::new(100, 100)).unwrap_err();
    assert!(
        matches!(
            err,
            WriteError::FrameSize {
                index: 2,
                got_width: 100,
                ..
            }
        ),
        "{err}"
    );
    assert_eq!(gif.frames_written(), 2);
    gif.finish().unwrap();

    let empty = GifWriter::create(dir.join("b.gif"), 480, 360, 30.0).unwrap();
    assert!(matches!(empty.finish(), Err(WriteError::NoFrames)));
    assert!(matches!(
        write_gif(dir.join("c.gif"), &[], 10.0),
        Err(WriteError::NoFrames)
    ));
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn gif_frame_rates_map_to_hundredths_and_bad_ones_are_refused() {
    assert_eq!(gif_delay_cs(50.0).unwrap(), 2);
    assert_eq!(gif_delay_cs(25.0).unwrap(), 4);
    assert_eq!(gif_delay_cs(30.0).unwrap(), 3);
    assert_eq!(gif_delay_cs(1.0).unwrap(), 100);
    for fps in [0.0, -5.0, 60.0, f64::NAN, f64::INFINITY] {
        let err = gif_delay_cs(fps).unwrap_err();
        assert!(matches!(err, WriteError::Fps { .. }), "{fps}: {err}");
    }
    let dir = scratch_dir("gif-fps");
    let err = GifWriter::create(dir.join("x.gif"), 480, 360, 0.0).unwrap_err();
    assert!(err.to_string().contains("frame rate 0"), "{err}");
    assert!(!dir.join("x.gif").exists(), "a refused GIF creates no file");
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn png_sequence_writes_numbered_lossless_frames() {
    let dir = scratch_dir("png-seq");
    let frames = frames(3);
    let out = dir.join("frames");
    let paths = write_png_sequence(&out, &frames).unwrap();
    assert_eq!(paths.len(), 3);
    let mut names: Vec<_> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    assert_eq!(
        names,
        ["frame_000000.png", "frame_000001.png", "frame_000002.png"]
    );
    for (path, frame) in paths.iter().zip(&frames) {
        let (w, h, rgb) = decode_png(path);
        assert_eq!((w, h), (480, 360));
        assert_eq!(&rgb, &frame.rgb, "PNG is lossless");
    }

    let mut seq = PngSequence::create(dir.join("mixed")).unwrap();
    seq.push(&frames[0]).unwrap();
    let err = seq.push(&Frame::new(64, 48)).unwrap_err();
    assert!(
        matches!(err, WriteError::FrameSize { index: 1, .. }),
        "{err}"
    );
    assert_eq!(seq.frames_written(), 1);
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn single_png_round_trips_and_bad_frames_or_paths_are_refused() {
    let dir = scratch_dir("png-one");
    let frame = frames(1).remove(0);
    let path = dir.join("one.png");
    write_png(&path, &frame).unwrap();
    assert_eq!(decode_png(&path), (480, 360, frame.rgb.clone()));

    let broken = Frame {
        width: 10,
        height: 10,
        rgb: vec![0; 299],
    };
    let err = write_png(dir.join("broken.png"), &broken).unwrap_err();
    assert!(
        matches!(err, WriteError::Inconsistent { len: 299, .. }),
        "{err}"
    );

    let err = write_png(dir.join("no/such/dir/x.png"), &frame).unwrap_err();
    assert!(err.to_string().contains("no/such/dir"), "{err}");
    std::fs::remove_dir_all(dir).unwrap();
}
