//! Options renamed so that each name means one thing in every command and each unit is spelt
//! one way, and `compensate`'s options retired for `--free`: the old spelling is refused with a
//! message naming the new one (exit code 2), before clap, which would only call it unknown.

/// Each renamed option: the command, the old spelling, the new one and why.
const RENAMED: [(&str, &str, &str, &str); 4] = [
    ("select", "--postures", "--count", "the number of postures; --postures is a postures file in evaluate, plot and simulate"),
    ("register", "--postures", "--count", "the number of postures to propose; --postures is a postures file in evaluate, plot and simulate"),
    ("compensate", "--force-tolerance-percent", "--force-tolerance-pct", "every percentage ends in -pct"),
    ("place", "--force-tolerance-percent", "--force-tolerance-pct", "every percentage ends in -pct"),
];

/// The message refusing the first renamed option of `args` (the command line after the
/// program's name), if it holds one.
pub fn refused<S: AsRef<str>>(args: &[S]) -> Option<String> {
    let args: Vec<&str> = args.iter().map(AsRef::as_ref).collect();
    let at = command(&args)?;
    let (command, options) = (args[at], &args[at + 1..]);
    renamed(command, options).or_else(|| retired(command, options))
}

/// An option of [`RENAMED`] among `command`'s `options`.
fn renamed(command: &str, options: &[&str]) -> Option<String> {
    let given =
        |old: &str, a: &str| a == old || a.strip_prefix(old).is_some_and(|r| r.starts_with('='));
    RENAMED.iter().find_map(|&(c, old, new, why)| {
        (c == command && options.iter().any(|a| given(old, a)))
            .then(|| format!("{old}: renamed {new} in `stiffid {command}` ({why})"))
    })
}

/// `place`'s options retired for `--free VARIABLE=LO..HI`: the old spelling and how to write it.
const PLACE_RETIRED: [(&str, &str); 2] = [
    (
        "--z-mm",
        "--free z=LO..HI (the height's range, mm from the part's own)",
    ),
    ("--tilt-deg", "--free tilt=-T..T (deg)"),
];

/// A retired option of `stiffid compensate` or `stiffid place` among its `options`, with how to
/// write it with `--free` (for compensate the library's table, which Python's `compensate`
/// refuses by too).
fn retired(command: &str, options: &[&str]) -> Option<String> {
    if command == "place" {
        return place_retired(options);
    }
    if command != "compensate" {
        return None;
    }
    options.iter().find_map(|a| {
        let name = a.strip_prefix("--")?.split('=').next()?;
        let (option, value) = stiffid::internal::machining::compensate::free::retired(name)?;
        Some(format!("--{name}: removed; write --{option} {value}"))
    })
}

/// A retired option of `stiffid place`, or its `--free` given without a value as it was a
/// switch (the six degrees of freedom).
fn place_retired(options: &[&str]) -> Option<String> {
    let given =
        |old: &str, a: &str| a == old || a.strip_prefix(old).is_some_and(|r| r.starts_with('='));
    let found = PLACE_RETIRED.iter().find_map(|&(old, new)| {
        (options.iter().any(|a| given(old, a))).then(|| format!("{old}: removed; write {new}"))
    });
    let bare =
        |i: usize| options[i] == "--free" && options.get(i + 1).is_none_or(|v| v.starts_with("--"));
    found.or_else(|| {
        (0..options.len()).any(bare).then(|| {
            "--free: expected a variable: --free z (the height, its own +-100 mm) and --free tilt (+-10 deg) for the six degrees of freedom, or z=LO..HI (mm from its own) and tilt=-T..T (deg)".to_string()
        })
    })
}

/// The index of the subcommand in `args`: the first word that is neither an option nor the
/// value of the global `--package-path DIR`.
fn command(args: &[&str]) -> Option<usize> {
    let mut i = 0;
    while i < args.len() {
        match args[i] {
            "--package-path" => i += 2,
            a if a.starts_with('-') => i += 1,
            _ => return Some(i),
        }
    }
    None
}
