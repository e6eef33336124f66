//! Text as a one-line message needs it.

/// `s` with control characters escaped (`\n`, `\u{1b}`...), so that a message naming something
/// a user typed (a gear's name with a newline in it, say) stays on one line and moves no
/// terminal's cursor.
pub fn one_line(s: &str) -> String {
    if !s.contains(char::is_control) {
        return s.to_owned();
    }
    let mut o = String::with_capacity(s.len() + 8);
    for c in s.chars() {
        if c.is_control() {
            o.extend(c.escape_default());
        } else {
            o.push(c);
        }
    }
    o
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn control_characters_are_escaped_and_the_rest_kept() {
        assert_eq!(one_line("gear b1"), "gear b1");
        assert_eq!(one_line("b1\nrm -rf"), "b1\\nrm -rf");
        assert_eq!(one_line("\u{1b}[2Jé\t"), "\\u{1b}[2Jé\\t");
    }
}
