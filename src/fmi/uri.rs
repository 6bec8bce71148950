//! `resourceLocation` URIs (fmi-notes.md §7): `file:///abs`, `file:/abs` and
//! `file://localhost/abs`, percent-encoded. Anything else means "no resources".

use std::path::PathBuf;

/// The local directory a `file:` URI names, or `None` for NULL, empty or non-file URIs.
pub fn resource_dir_from_uri(uri: &str) -> Option<PathBuf> {
    let rest = uri.strip_prefix("file:")?;
    let path = if let Some(after) = rest.strip_prefix("//") {
        // authority form: `file:///abs` (empty authority) or `file://localhost/abs`
        let slash = after.find('/')?;
        let authority = &after[..slash];
        if !(authority.is_empty() || authority.eq_ignore_ascii_case("localhost")) {
            return None;
        }
        &after[slash..]
    } else {
        rest
    };
    if !path.starts_with('/') {
        return None;
    }
    percent_decode(path).map(PathBuf::from)
}

fn percent_decode(s: &str) -> Option<String> {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = std::str::from_utf8(bytes.get(i + 1..i + 3)?).ok()?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn accepts_the_three_file_forms_and_decodes() {
        let want = Some(PathBuf::from("/tmp/a b/resources"));
        assert_eq!(resource_dir_from_uri("file:///tmp/a%20b/resources"), want);
        assert_eq!(resource_dir_from_uri("file:/tmp/a%20b/resources"), want);
        assert_eq!(
            resource_dir_from_uri("file://localhost/tmp/a%20b/resources"),
            want
        );
    }

    #[test]
    fn rejects_other_uris() {
        assert_eq!(resource_dir_from_uri(""), None);
        assert_eq!(resource_dir_from_uri("http://x/y"), None);
        assert_eq!(resource_dir_from_uri("file://otherhost/y"), None);
        assert_eq!(resource_dir_from_uri("file:relative"), None);
        assert_eq!(resource_dir_from_uri("file:///bad%zz"), None);
    }
}
