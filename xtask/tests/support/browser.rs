//! The headless-browser harness of the page and figure tests: run Chromium on a page within a
//! time limit (its DOM after the page's script ran, or a screenshot), and read a screenshot's
//! pixels back to judge that it is not blank.

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::Duration;

/// How long Chromium may take on one page.
const LIMIT: Duration = Duration::from_secs(90);

/// Runs `chrome` headless on `url` with `extra` arguments and the profile folder `profile`,
/// within [`LIMIT`]; its stdout (the DOM under `--dump-dom`). Chromium's stderr goes to
/// `profile`'s sibling `chromium.log`, for a failure to be looked at.
pub fn headless(chrome: &Path, profile: &Path, extra: &[String], url: &str) -> String {
    let log = profile.with_extension("log");
    let child = Command::new(chrome)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--hide-scrollbars",
        ])
        .args(extra)
        .arg(format!("--user-data-dir={}", profile.display()))
        .arg(url)
        .stdout(Stdio::piped())
        .stderr(
            std::fs::File::create(&log)
                .map(Stdio::from)
                .unwrap_or_else(|_| Stdio::null()),
        )
        .spawn()
        .unwrap();
    // Read while Chromium writes (a full pipe would stall it), with a time limit.
    let pid = child.id();
    let (done, got) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let _ = done.send(child.wait_with_output());
    });
    let out = got
        .recv_timeout(LIMIT)
        .unwrap_or_else(|_| {
            let _ = Command::new("kill").arg(pid.to_string()).status();
            panic!("chromium took more than {} s on {url}", LIMIT.as_secs())
        })
        .unwrap();
    assert!(
        out.status.success(),
        "chromium failed on {url} ({}; see {})",
        out.status,
        log.display()
    );
    String::from_utf8(out.stdout).unwrap()
}

/// The DOM of `url` after its script ran.
pub fn dump_dom(chrome: &Path, profile: &Path, url: &str) -> String {
    headless(chrome, profile, &["--dump-dom".to_owned()], url)
}

/// A screenshot of `url` in a window of `width` × `height` pixels, written to `png`.
pub fn screenshot(
    chrome: &Path,
    profile: &Path,
    url: &str,
    png: &Path,
    (width, height): (u32, u32),
) {
    headless(
        chrome,
        profile,
        &[
            format!("--window-size={width},{height}"),
            format!("--screenshot={}", png.display()),
        ],
        url,
    );
}

/// A screenshot's pixels as RGB.
pub struct Pixels {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Row by row, left to right.
    pub rgb: Vec<[u8; 3]>,
}

impl Pixels {
    /// Reads `png`.
    pub fn read(png: &Path) -> Self {
        let bytes = std::fs::read(png).unwrap();
        assert!(!bytes.is_empty(), "{} is empty", png.display());
        let mut decoder = png::Decoder::new(std::io::Cursor::new(bytes));
        decoder.set_transformations(png::Transformations::normalize_to_color8());
        let mut reader = decoder.read_info().unwrap();
        let mut buf = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut buf).unwrap();
        let channels = info.color_type.samples();
        let rgb = buf
            .chunks(info.line_size)
            .take(info.height as usize)
            .flat_map(|row| {
                row[..info.width as usize * channels]
                    .chunks(channels)
                    .map(|p| [p[0], p[1], p[2]])
            })
            .collect();
        Self {
            width: info.width,
            height: info.height,
            rgb,
        }
    }

    /// How many distinct colours.
    pub fn colours(&self) -> usize {
        self.rgb
            .iter()
            .collect::<std::collections::HashSet<_>>()
            .len()
    }

    /// How many pixels are strongly coloured (far from grey): plot lines and marks.
    pub fn chromatic(&self) -> usize {
        self.rgb
            .iter()
            .filter(|p| p[0].max(p[1]).max(p[2]) - p[0].min(p[1]).min(p[2]) > 120)
            .count()
    }

    /// How many pixels are not near white.
    pub fn ink(&self) -> usize {
        self.rgb
            .iter()
            .filter(|p| u16::from(p[0]) + u16::from(p[1]) + u16::from(p[2]) < 600)
            .count()
    }

    /// Asserts a real picture, not a blank page: at least `colours` colours and `chromatic`
    /// strongly coloured pixels.
    pub fn assert_not_blank(&self, what: &str, colours: usize, chromatic: usize) {
        assert!(
            self.colours() >= colours,
            "{what}: blank screenshot, {} colours",
            self.colours()
        );
        assert!(
            self.chromatic() >= chromatic,
            "{what}: no coloured lines or marks, {} strongly coloured pixels",
            self.chromatic()
        );
    }
}
