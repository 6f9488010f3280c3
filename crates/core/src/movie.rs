//! Frames written one after another as an animation: a folder of PNG
//! frames, an animated GIF, or an MP4 encoded by `ffmpeg` (started as a
//! child process, frames piped to it as raw RGB). Every frame is an
//! [`Image`] composited over the background as its PNG would be.

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};

use glam::Vec3;

use crate::{Image, ImageError};

/// Why an animation could not be written.
#[derive(Debug, thiserror::Error)]
pub enum MovieError {
    #[error("{path}: write a .gif, a .mp4, or a folder of PNG frames (a path ending in /)")]
    Kind { path: PathBuf },
    #[error(
        "{path}: MP4 is written by ffmpeg, which could not be started ({source}); install \
         ffmpeg, or write a .gif or a folder of PNG frames"
    )]
    NoFfmpeg {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("MP4 (yuv420p) needs an even width and height, not {width}x{height}")]
    OddSize { width: u32, height: u32 },
    #[error("frame {index} is {got:?}, the animation's frames are {size:?}")]
    FrameSize {
        index: usize,
        got: (u32, u32),
        size: (u32, u32),
    },
    #[error("{path}: {source}")]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("{path}: {source}")]
    Encode {
        path: PathBuf,
        #[source]
        source: image::ImageError,
    },
    #[error("{path}: ffmpeg failed ({status})")]
    Ffmpeg { path: PathBuf, status: String },
    #[error(transparent)]
    Image(#[from] ImageError),
}

enum Sink {
    Folder,
    Gif(Box<image::codecs::gif::GifEncoder<std::fs::File>>),
    Mp4(Child),
}

/// An animation being written.
pub struct Movie {
    path: PathBuf,
    size: (u32, u32),
    fps: u32,
    background: Vec3,
    frames: usize,
    sink: Sink,
}

impl Movie {
    /// Starts the animation at `path`: a folder of PNG frames
    /// (`frame_0000.png` ...) when the path ends in `/` or is a folder,
    /// else by its extension, `.gif` or `.mp4`.
    pub fn create(
        path: &Path,
        (width, height): (u32, u32),
        fps: u32,
        background: Vec3,
    ) -> Result<Movie, MovieError> {
        let io = |source| MovieError::Io {
            path: path.to_path_buf(),
            source,
        };
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        let folder = path.to_string_lossy().ends_with('/') || path.is_dir();
        let fps = fps.max(1);
        let sink = match ext.as_deref() {
            _ if folder => {
                std::fs::create_dir_all(path).map_err(io)?;
                Sink::Folder
            }
            Some("gif") => {
                let file = std::fs::File::create(path).map_err(io)?;
                let mut gif = image::codecs::gif::GifEncoder::new_with_speed(file, 10);
                gif.set_repeat(image::codecs::gif::Repeat::Infinite)
                    .map_err(|source| MovieError::Encode {
                        path: path.to_path_buf(),
                        source,
                    })?;
                Sink::Gif(Box::new(gif))
            }
            Some("mp4") => {
                if width % 2 == 1 || height % 2 == 1 {
                    return Err(MovieError::OddSize { width, height });
                }
                let child = Command::new("ffmpeg")
                    .args([
                        "-loglevel",
                        "error",
                        "-y",
                        "-f",
                        "rawvideo",
                        "-pix_fmt",
                        "rgb24",
                    ])
                    .args(["-s", &format!("{width}x{height}"), "-r", &fps.to_string()])
                    .args(["-i", "-", "-an", "-c:v", "libx264", "-pix_fmt", "yuv420p"])
                    .arg(path)
                    .stdin(Stdio::piped())
                    .spawn()
                    .map_err(|source| MovieError::NoFfmpeg {
                        path: path.to_path_buf(),
                        source,
                    })?;
                Sink::Mp4(child)
            }
            _ => {
                return Err(MovieError::Kind {
                    path: path.to_path_buf(),
                });
            }
        };
        Ok(Movie {
            path: path.to_path_buf(),
            size: (width, height),
            fps,
            background,
            frames: 0,
            sink,
        })
    }

    /// Frames written so far.
    pub fn frames(&self) -> usize {
        self.frames
    }

    /// Adds the next frame.
    pub fn add(&mut self, image: &Image) -> Result<(), MovieError> {
        if (image.width, image.height) != self.size {
            return Err(MovieError::FrameSize {
                index: self.frames,
                got: (image.width, image.height),
                size: self.size,
            });
        }
        let frame = image.to_rgb8(self.background)?;
        let encode = |source| MovieError::Encode {
            path: self.path.clone(),
            source,
        };
        match &mut self.sink {
            Sink::Folder => {
                let path = self.path.join(format!("frame_{:04}.png", self.frames));
                frame
                    .save_with_format(&path, image::ImageFormat::Png)
                    .map_err(|source| MovieError::Encode { path, source })?;
            }
            Sink::Gif(gif) => {
                let rgba = image::DynamicImage::ImageRgb8(frame).into_rgba8();
                let delay = image::Delay::from_numer_denom_ms(1000, self.fps);
                gif.encode_frame(image::Frame::from_parts(rgba, 0, 0, delay))
                    .map_err(encode)?;
            }
            Sink::Mp4(child) => {
                let written = match child.stdin.as_mut() {
                    Some(stdin) => stdin.write_all(frame.as_raw()),
                    None => Err(std::io::ErrorKind::BrokenPipe.into()),
                };
                written.map_err(|source| MovieError::Io {
                    path: self.path.clone(),
                    source,
                })?;
            }
        }
        self.frames += 1;
        Ok(())
    }

    /// Ends the animation (waits for ffmpeg to finish the MP4).
    pub fn finish(self) -> Result<(), MovieError> {
        if let Sink::Mp4(mut child) = self.sink {
            drop(child.stdin.take());
            let status = child.wait().map_err(|source| MovieError::Io {
                path: self.path.clone(),
                source,
            })?;
            if !status.success() {
                return Err(MovieError::Ffmpeg {
                    path: self.path,
                    status: status.to_string(),
                });
            }
        }
        Ok(())
    }
}
