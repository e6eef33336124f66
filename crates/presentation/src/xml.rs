//! Text made safe for SVG and HTML: below the charts and pages, which all escape through it.

/// `s` with the characters XML text and attributes must escape escaped (`&`, `<`, `>`, `"`):
/// for SVG and HTML pages.
pub fn escape_xml(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}
