//! The files of a controller's backup a program is read with: what the controller holds
//! beside the program and the program uses by name or number (FANUC `SYSFRAME.VA`, the user and
//! tool frames; Yaskawa `TOOL.CND`, the tool files). A reader looks a file up by its name
//! ([`Backup::file`]); what the backup gives needs no table in the setup, and a number both
//! give differently is refused naming both.

use stiffid_core::{Error, Result};

/// One file of a backup: its name as given (a path) and its text.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BackupFile {
    /// The file's name as given, a path: what errors name.
    pub name: String,
    /// Its text.
    pub text: String,
}

/// The files of a controller's backup (module docs), each found by its file name.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Backup {
    files: Vec<BackupFile>,
}

impl Backup {
    /// A backup of `files` (name, a path, and text).
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`backup`) naming both when two files have one file name (case
    /// aside: a controller's file system does not tell `TOOL.CND` from `tool.cnd`).
    pub fn new(files: Vec<(String, String)>) -> Result<Self> {
        let files: Vec<BackupFile> = (files.into_iter())
            .map(|(name, text)| BackupFile { name, text })
            .collect();
        for (i, f) in files.iter().enumerate() {
            if let Some(g) = files[..i].iter().find(|g| same_name(&g.name, &f.name)) {
                return Err(Error::InvalidField {
                    field: "backup".into(),
                    message: format!("{} and {}: two files of one name; a controller's backup holds one of each: give one", g.name, f.name),
                });
            }
        }
        Ok(Backup { files })
    }

    /// The file whose name (the last part of its path) is `name`, case aside, if the backup
    /// holds one.
    pub fn file(&self, name: &str) -> Option<&BackupFile> {
        self.files.iter().find(|f| same_name(&f.name, name))
    }

    /// Every file, in the order given.
    pub fn files(&self) -> &[BackupFile] {
        &self.files
    }
}

/// Whether two paths name one file name, case aside.
fn same_name(a: &str, b: &str) -> bool {
    file_name(a).eq_ignore_ascii_case(file_name(b))
}

/// The last part of a path (after its last `/` or `\`).
fn file_name(path: &str) -> &str {
    path.rsplit(['/', '\\']).next().unwrap_or(path)
}
