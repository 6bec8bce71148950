//! `resourceLocation` URIs: `file:///abs`, `file:/abs` and `file://localhost/abs`,
//! percent-encoded (hosts differ in the form; FMPy sends `file:///…`). On Windows the path part
//! of `file:///C:/dir` is `C:/dir`. Anything else means "no resources".

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
    let path = percent_decode(path)?;
    if cfg!(windows) {
        if let Some(native) = without_drive_slash(&path) {
            return Some(PathBuf::from(native));
        }
    }
    Some(PathBuf::from(path))
}

/// `C:/dir` for the URI path `/C:/dir` (a Windows drive letter), else `None`.
fn without_drive_slash(path: &str) -> Option<&str> {
    let b = path.as_bytes();
    (b.len() >= 3 && b[0] == b'/' && b[1].is_ascii_alphabetic() && b[2] == b':').then(|| &path[1..])
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
    fn windows_drive_letters_lose_the_leading_slash() {
        assert_eq!(
            without_drive_slash("/C:/a b/resources"),
            Some("C:/a b/resources")
        );
        assert_eq!(without_drive_slash("/c:"), Some("c:"));
        assert_eq!(without_drive_slash("/tmp/resources"), None);
        assert_eq!(without_drive_slash("/1:/x"), None);
        let decoded = resource_dir_from_uri("file:///C:/a%20b/resources");
        let want = if cfg!(windows) {
            "C:/a b/resources"
        } else {
            "/C:/a b/resources"
        };
        assert_eq!(decoded, Some(PathBuf::from(want)));
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
