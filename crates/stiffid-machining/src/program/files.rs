//! A program's files: those it is read from (its own, KRL's `.dat` beside it, the controller
//! backup's), and the programs of the backup it calls, whose texts follow its own
//! ([`Read::called`](super::Read::called)).

use super::{Dialect, JointProgram, JointTarget};
use std::ops::Range;
use stiffid_core::Error;

/// The data file a program at `path` keeps beside it: the first of its language's
/// [`super::Descriptor::data_files`] (KRL's `.dat`) of the same folder and stem
/// ([`stiffid_core::io::input::beside`]); `None` for a language without one, for a data file
/// itself, or where there is none.
pub(crate) fn data_beside(path: &std::path::Path) -> Option<std::path::PathBuf> {
    let extension = path.extension()?.to_str()?.to_ascii_lowercase();
    let Some(crate::Language::Robot(dialect)) = crate::Language::from_extension(&extension) else {
        return None;
    };
    let controller = dialect.controller();
    if controller.refuses_output(&extension).is_some() {
        return None;
    }
    let (data, _) = controller.descriptor().data_files.first()?;
    stiffid_core::io::input::beside(path, data)
}

/// The data file a program written to `out` keeps beside it: of its language's first
/// [`super::Descriptor::data_files`] extension (KRL's `.dat`), in upper case where all of
/// `out`'s extension is (`X.SRC` with `X.DAT`); `None` for a language without one.
pub fn data_out(out: &std::path::Path) -> Option<std::path::PathBuf> {
    let extension = out.extension()?.to_str()?;
    let Some(crate::Language::Robot(dialect)) = crate::Language::from_extension(extension) else {
        return None;
    };
    let controller = dialect.controller();
    if controller
        .refuses_output(&extension.to_ascii_lowercase())
        .is_some()
    {
        return None;
    }
    let (data, _) = controller.descriptor().data_files.first()?;
    let upper = extension.chars().all(|c| c.is_ascii_uppercase());
    Some(out.with_extension(match upper {
        true => data.to_ascii_uppercase(),
        false => data.to_string(),
    }))
}

/// The text of the program at `path`, of the data file its language keeps beside it where
/// there is one (`data_beside`: KRL's `.dat` of a `.src`), and the encoding they were read in: UTF-8, else Latin-1
/// ([`stiffid_core::io::program_texts`]). `read` gives a file's bytes (a front end's reading,
/// with the file's name in its error); `wrap` turns a text's error into the caller's.
///
/// # Errors
/// Those of `read`, and of [`stiffid_core::io::program_texts`] through `wrap`.
pub fn read_files<E>(
    path: &std::path::Path,
    mut read: impl FnMut(&std::path::Path) -> std::result::Result<Vec<u8>, E>,
    wrap: impl Fn(Error) -> E,
) -> std::result::Result<(String, Option<String>, stiffid_core::io::Encoding), E> {
    let data = data_beside(path);
    let mut files = Vec::new();
    for p in [Some(path), data.as_deref()].into_iter().flatten() {
        files.push((p.display().to_string(), read(p)?));
    }
    let named = files.iter().map(|(n, b)| (n.as_str(), b.clone())).collect();
    let (mut texts, encoding) = stiffid_core::io::program_texts(named).map_err(wrap)?;
    let data = (texts.len() == 2).then(|| texts.remove(1));
    Ok((texts.remove(0), data, encoding))
}

/// The files of a controller's backup given with a program of `dialect` (`paths`: files, or
/// folders whose files of the language's backup extensions are read,
/// [`stiffid_core::io::input::files_under`]), each named as found and its text (UTF-8, else
/// Latin-1). `read` gives a file's bytes (a front end's reading, with the file's name in its
/// error); `wrap` turns a listing's or a text's error into the caller's.
///
/// A file of a folder that is not text (an encrypted module, a stray control byte) is passed
/// over, but one the language reads by name (INFORM's `VAR.DAT`, `TOOL.CND`, `UFRAME.CND`); a
/// file given by name must be text.
///
/// # Errors
/// Those of `read`; a path that cannot be listed, or a file given by name that is not text,
/// through `wrap`.
pub fn read_backup<E>(
    paths: &[std::path::PathBuf],
    dialect: Dialect,
    mut read: impl FnMut(&std::path::Path) -> std::result::Result<Vec<u8>, E>,
    wrap: impl Fn(Error) -> E,
) -> std::result::Result<Vec<(String, String)>, E> {
    let extensions = dialect.controller().backup_extensions();
    let wanted = |name: &str| {
        let e = name
            .rsplit_once('.')
            .map_or("", |(_, e)| e)
            .to_ascii_lowercase();
        extensions.contains(&e.as_str())
    };
    // A file the language reads by name (INFORM's `VAR.DAT`) that is no text is refused: passed
    // over, what it holds would be asked for as if it were not given.
    let by_name = |file: &std::path::Path| {
        let name = file
            .file_name()
            .map_or(String::new(), |n| n.to_string_lossy().to_ascii_uppercase());
        dialect.controller().backup_names().contains(&name.as_str())
    };
    let mut out = Vec::new();
    for path in paths {
        let files = stiffid_core::io::input::files_under(path, &wanted).map_err(|e| {
            wrap(Error::Parse {
                source_name: path.display().to_string(),
                message: format!("the controller's backup: {e}"),
            })
        })?;
        // The path itself (a file given by name) or the files of a folder.
        let listed = files.as_slice() != std::slice::from_ref(path);
        for file in files {
            let name = file.display().to_string();
            let bytes = read(&file)?;
            match stiffid_core::io::program_texts(vec![(name.as_str(), bytes)]) {
                Ok((mut texts, _)) => out.push((name, texts.remove(0))),
                // A folder's module that is no text (encrypted, or a control byte the
                // controller's editor left) declares nothing stiffid can read: a point the
                // program takes from it is refused as declared nowhere.
                Err(_) if listed && !by_name(&file) => {}
                Err(e) => return Err(wrap(e)),
            }
        }
    }
    twice(&out, dialect).map_or(Ok(out), |e| Err(wrap(e)))
}

/// The refusal of two different files of one name (case aside) in a backup where the
/// controller holds one ([`Controller::held_once`](super::Controller::held_once)): which one
/// it holds is not the files' to say (two controllers' backups given together, say).
fn twice(files: &[(String, String)], dialect: Dialect) -> Option<Error> {
    let controller = dialect.controller();
    files.iter().enumerate().find_map(|(i, (name, text))| {
        let short = super::file_name(name);
        let other = files[..i].iter().find(|(n, t)| {
            super::file_name(n).eq_ignore_ascii_case(short) && t != text
        })?;
        controller.held_once(short).then(|| Error::Parse {
            source_name: name.clone(),
            message: format!(
                "the controller's backup holds two different files named {short}: {} and this one; a controller holds one: give one controller's backup",
                other.0
            ),
        })
    })
}

impl JointProgram {
    /// The file of the backup (its name as given) whose motion target `i` is: a program the
    /// program calls ([`Read::called`](super::Read::called)); `None` for the program's own.
    pub fn called_in(&self, i: usize) -> Option<&str> {
        let start = self.targets.get(i)?.spans[0].start;
        let t = &self.targets[i];
        let start = match (&t.cartesian, t.point.as_deref()) {
            // A motion whose numbers are another file's (a bound parameter): where it is.
            _ if t.motion_at.is_some() => t.motion_at.unwrap_or(start),
            // A copy of another file's point goes where its declaration does.
            (_, Some(p)) if p.foreign.is_some() => p.declaration.start,
            (Some(c), _) => c.spans.first().map_or(start, |s| s.start),
            (None, _) => start,
        };
        (self.called.iter().rev())
            .find(|(_, at)| *at <= start)
            .map(|(name, _)| name.as_str())
    }
}

impl JointTarget {
    /// The target with every span moved `offset` bytes on: read in a text that follows others
    /// (a called program's, [`Read::called`](super::Read::called)).
    pub(crate) fn shifted(mut self, offset: usize) -> Self {
        let shift = |r: &mut Range<usize>| *r = r.start + offset..r.end + offset;
        self.motion_at = self.motion_at.map(|a| a + offset);
        self.spans.iter_mut().for_each(shift);
        self.external_spans.iter_mut().flatten().for_each(shift);
        if let Some(c) = self.cartesian.as_deref_mut() {
            c.spans.iter_mut().for_each(shift);
            c.flag_spans.iter_mut().for_each(|(r, _)| shift(r));
        }
        if let Some(p) = self.point.as_deref_mut() {
            *p = p.clone().shifted(offset);
        }
        self
    }
}

impl super::points::Point {
    /// The point with every span moved `offset` bytes on ([`JointTarget::shifted`]).
    pub(crate) fn shifted(mut self, offset: usize) -> Self {
        let shift = |r: &mut Range<usize>| *r = r.start + offset..r.end + offset;
        shift(&mut self.declaration);
        self.reference.iter_mut().for_each(shift);
        // A point of another file: its name is in the copy's text, the spans' base moves.
        match self.foreign.as_deref_mut() {
            Some(f) => f.at += offset,
            None => shift(&mut self.name),
        }
        self
    }
}

#[cfg(test)]
mod tests {
    use super::{twice, Dialect};

    fn files(list: &[(&str, &str)]) -> Vec<(String, String)> {
        (list.iter())
            .map(|(n, t)| (n.to_string(), t.to_string()))
            .collect()
    }

    #[test]
    fn two_different_files_of_one_name_are_refused_naming_both() {
        let two = files(&[("a/POSREG.VA", "x"), ("b/posreg.va", "y")]);
        let message = twice(&two, Dialect::FanucLs).expect("refused").to_string();
        assert!(
            message.contains("b/posreg.va") && message.contains("a/POSREG.VA"),
            "{message}"
        );
        // The same file given twice (a folder and a file of it) is one file.
        assert!(twice(
            &files(&[("a/P.LS", "x"), ("a/P.LS", "x")]),
            Dialect::FanucLs
        )
        .is_none());
        // A KSS backup's two `$machine.dat` (the controller's and the robot's) are the system's.
        let kss = files(&[
            ("STEU/Mada/$machine.dat", "x"),
            ("R1/Mada/$machine.dat", "y"),
        ]);
        assert!(twice(&kss, Dialect::Krl).is_none());
        let config = files(&[("R1/System/$config.dat", "x"), ("old/$CONFIG.DAT", "y")]);
        assert!(twice(&config, Dialect::Krl).is_some());
    }
}
