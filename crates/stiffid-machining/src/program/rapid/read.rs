//! A RAPID module read statement by statement (module docs of [`super`]): every motion of every
//! routine, each where it is (inside `IF`, `WHILE`, `FOR`, `TEST`, an error handler, any `PROC`),
//! in the order of the text. A motion names its own tool, work object and speed, so what it
//! moves with is the same on every path; what a statement sets for the motions after it,
//! `ConfJ`/`ConfL \Off` (configuration monitoring), is followed through the branches and loops
//! ([`crate::program::paths`]) and is the caller's at a routine's start.

use super::assign::{self, Bound};
use super::called::{Bindings, Task, MAX_READS};
use super::calls::{self, routine};
use super::layout::Layout;
use super::numflow::Values;
use super::state::{Conf, Entry, Here, Module};
use super::{declarations, first_word, flow, is_header, motion, no_motion, statements};
use super::{well_formed, without_comments, Data, Statement};
use crate::program::controller::Read;
use crate::program::paths::{Kind, Paths};
use crate::program::{at, Context, JointTarget, Left};
use stiffid_core::{Error, Result};

/// Every target of `text`, in the order of its motions (module docs), the program's external
/// axes (`eax_a` to the last one any target gives a value, not `9E9`), the motions left as
/// found ([`Context::leave_refused`]) and the modules of the task it calls that move (module
/// `called`).
///
/// # Errors
/// [`stiffid_core::Error::Program`] naming the line of a motion outside the subset, of a motion
/// whose configuration monitoring depends on the path (unless left as found), of a jump in a
/// module that switches configuration monitoring, of a call refused (module `calls`), or of a
/// module without motions.
pub(crate) fn targets(text: &str, context: &Context) -> Result<Read> {
    let (procs, twice) = calls::procedures(context, text);
    let mut task = Task {
        procs,
        twice,
        total: text.len(),
        program: vec![("the program".to_string(), text.to_string())],
        ..Task::default()
    };
    let module = module(text, 0, None, context, &mut task)?;
    let (out, left) = (module.targets, module.left);
    if out.is_empty() && left.is_empty() {
        return Err(at(1, no_motion(&module.routines)));
    }
    let n = out
        .iter()
        .filter_map(|t| t.external.iter().rposition(Option::is_some))
        .max()
        .map_or(0, |k| k + 1);
    let axes = (0..n).map(|k| format!("eax_{}", (b'a' + k as u8) as char));
    Ok(Read {
        targets: out,
        axes: axes.collect(),
        left,
        called: task.files,
        ..Read::default()
    })
}

/// The module `text`, its text at byte `offset` of the whole text: every routine's motions, or
/// with `entry` the called procedure's and those of the module's routines it calls.
fn module(
    text: &str,
    offset: usize,
    entry: Option<&Entry>,
    context: &Context,
    task: &mut Task,
) -> Result<Module> {
    let (code, statements, mut data) = prepared(text, offset, entry, context, task)?;
    let switches_conf = switching(&code, &statements);
    let layout = Layout::of(
        &code,
        &statements,
        task,
        entry.map(|e| (e.name.as_str(), e.place, e.alone)),
    );
    let start = (switches_conf, &layout);
    let (mut out, mut left) = (Vec::new(), Vec::new());
    let mut routines: Vec<(String, u64)> = Vec::new();
    let mut flow = flow::Flow::default();
    let mut paths: Paths<Conf> = Paths::default();
    let mut conf = Conf([Ok(false), Ok(false)], Bound::new(), Values::new());
    // The first motion of the routine being read.
    let mut first_motion: Option<u64> = None;
    let order = super::unroll::order(&code, &statements, &data.nums)?;
    // The loop variables' values in force, and the data they hide.
    let mut hidden: Vec<(String, Option<std::result::Result<f64, String>>)> = Vec::new();
    for (k, values) in order {
        let s = &statements[k];
        loop_values(&mut data, &mut hidden, values);
        if !layout.read[k] {
            continue;
        }
        let body = &code[s.span.clone()];
        let first = first_word(body);
        well_formed(s.line, &body.trim_start()[..first.len()])?;
        if let Some(name) = routine(body) {
            check_jumps(&flow, &routines, first_motion.take(), switches_conf)?;
            routines.push((name, s.line));
            flow.routine();
            paths.clear();
            conf = at_routine(entry, start, (&routines, body), &mut data, s.line);
            continue;
        }
        flow.statement(&first, is_header(body), s.line);
        let step = (k, first.as_str(), is_header(body));
        let read = (code.as_str(), &statements[..]);
        structure(step, read, &mut paths, (&mut data, &mut conf), &routines);
        let here = Here {
            statement: s,
            place: layout.places[k],
            module: (text, offset),
        };
        if first == "if" && !is_header(body) {
            let called = calls::in_compact_if(body).map(|(n, _)| (n, s.line));
            forget_called(called, (&layout, &routines), (&mut data, &mut conf));
            compact_if(
                &here,
                (&code, body),
                (&data, &conf),
                context,
                (&mut out, &mut left),
                &mut flow,
                task,
                &layout,
            )?;
            continue;
        }
        let rest = body.trim_start()[first.len()..].trim_start();
        if rest.starts_with([':', '.', '{']) {
            // An assignment: a point the module assigns whole takes its value (`assign`).
            let read = (s, code.as_str(), first.as_str());
            assign::statement(read, &name_of(&routines), &data, &mut conf.1);
            continue;
        }
        if let Some(k) = ["confj", "confl"].iter().position(|c| *c == first) {
            conf.0[k] = Ok(rest.to_ascii_lowercase().starts_with("\\off"));
        }
        if let Some(name) = calls::called(body, &first) {
            let called = Some((name, s.line));
            forget_called(called, (&layout, &routines), (&mut data, &mut conf));
            let call = (name, &body.trim_start()[name.len()..]);
            let found = call_of(&here, call, (&data, &mut conf), context, task, &layout);
            keep(found, context, (&mut out, &mut left))?;
            continue;
        }
        if let (Some(why), true) = (calls::shifts(&first), here.place.before_last) {
            let name = &body.trim_start()[..first.len()];
            context.leave(&mut left, at(s.line, format!("{name}: {why}")))?;
            continue;
        }
        let found = match moves(s, &code, &first, &data, &conf) {
            Ok(found) => found,
            Err(e) => {
                context.leave(&mut left, e)?;
                continue;
            }
        };
        if !found.is_empty() {
            first_motion.get_or_insert(s.line);
        }
        out.extend(found);
    }
    check_jumps(&flow, &routines, first_motion, switches_conf)?;
    Ok(Module {
        targets: out,
        left,
        routines: routines_of(&code, &statements),
        switches_conf: switches_conf.is_some(),
        switches_own: switches_read(&code, &statements, &layout.read),
    })
}

/// What is in force at the start of the routine on `line` (the last of `routines`): the caller's
/// configuration monitoring for the procedure another module calls (`entry`), else the start's
/// (`switches`: where the module switches it; the `layout`'s routines it calls); the assigned
/// points' values the run's ([`assign::Rebound::at_start`]); its parameters (its header `body`)
/// hiding the module's data of their names, bound to the call's arguments for the `entry`.
fn at_routine(
    entry: Option<&Entry>,
    (switches, layout): (Option<&Statement>, &Layout),
    (routines, body): (&[(String, u64)], &str),
    data: &mut Data,
    line: u64,
) -> Conf {
    let name = name_of(routines);
    let name = name.as_str();
    super::parameters::shadow(line, body, data);
    if let Some(e) = entry.filter(|e| e.name == name) {
        e.bindings.apply(data);
    }
    let mut conf = match entry.filter(|e| e.name == name) {
        Some(e) => e.conf.clone(),
        None => conf_at_start(switches.filter(|_| layout.called.contains(name)), line),
    };
    conf.1 = data.rebound.at_start(name, line);
    conf.2 = data.renum.at_start(name, line);
    conf
}

/// Follows the statement `k` of `statements` (`code`), its first word `first`, `header` whether
/// a structure line: a branch or loop it opens, divides or closes ([`branches`]), the points a
/// loop assigns ([`assign::Rebound::at_loop`]), the `num` data it sets in `routine` (module
/// `numflow`) in the last of `routines`; the assigned points' and `num` data's values into
/// `data`.
fn structure(
    (k, first, header): (usize, &str, bool),
    (code, statements): (&str, &[Statement]),
    paths: &mut Paths<Conf>,
    (data, conf): (&mut Data, &mut Conf),
    routines: &[(String, u64)],
) {
    if header {
        branches(first, statements[k].line, paths, conf);
        if matches!(first, "while" | "for") {
            data.rebound.at_loop((code, statements), k, &mut conf.1);
            data.renum.at_loop((code, statements), k, &mut conf.2);
        }
    }
    if !data.rebound.is_empty() {
        data.bound.clone_from(&conf.1);
    }
    if !data.renum.is_empty() {
        let s = &statements[k];
        let read = (&code[s.span.clone()], first, s.line);
        (data.renum).statement(read, &name_of(routines), &data.nums, &mut conf.2);
        data.renum.lay(&conf.2, &mut data.nums);
    }
}

/// After a call of `called` (its name as written and its line) of a routine of the module (the
/// `layout`'s, from the last of `routines`): the points another routine assigns are the run's.
fn forget_called(
    called: Option<(&str, u64)>,
    (layout, routines): (&Layout, &[(String, u64)]),
    (data, conf): (&mut Data, &mut Conf),
) {
    let Some((name, line)) = called else {
        return;
    };
    let name = name.to_ascii_lowercase();
    if layout.routines.contains(&name) {
        (data.rebound).after_call((&name, line), &name_of(routines), &mut conf.1);
        data.bound.clone_from(&conf.1);
        (data.renum).after_call((&name, line), &name_of(routines), &mut conf.2);
        data.renum.lay(&conf.2, &mut data.nums);
    }
}

/// The module `text` at byte `offset` of the whole text, its comments blanked and blank bytes
/// before it (its spans are the whole text's), its statements and its data: its own, the task's
/// other modules' (the program's too, for a module called) and, with `entry`, the call's
/// arguments.
fn prepared(
    text: &str,
    offset: usize,
    entry: Option<&Entry>,
    context: &Context,
    task: &Task,
) -> Result<(String, Vec<Statement>, Data)> {
    let code = " ".repeat(offset) + &without_comments(text);
    let statements = statements(&code);
    super::layout::routines_closed(&code, &statements)?;
    let shown = match entry {
        None => context.backup.to_vec(),
        Some(_) => [context.backup, &task.program].concat(),
    };
    let seen_by = Context {
        backup: &shown,
        ..*context
    };
    let own = declarations(&code, &statements)?;
    let mut data = super::backup::merge(own, (text, &code), &seen_by)?;
    data.rebound = assign::Rebound::of(&code, &statements);
    data.rebound.refuse_others(&mut data.assigned);
    if let Some(e) = entry {
        e.bindings.apply(&mut data);
    }
    Ok((code, statements, data))
}

/// The loop variables `values` in force in `data`'s `num` data, the ones in force before
/// (`hidden`: each name and the datum it hid) taken back.
fn loop_values(
    data: &mut Data,
    hidden: &mut Vec<(String, Option<std::result::Result<f64, String>>)>,
    values: Vec<(String, f64)>,
) {
    for (name, old) in hidden.drain(..) {
        match old {
            Some(o) => _ = data.nums.insert(name, o),
            None => _ = data.nums.remove(&name),
        }
    }
    for (name, v) in values {
        let old = data.nums.insert(name.clone(), Ok(v));
        hidden.push((name, old));
    }
}

/// Every routine of the module `code` (its `statements`): name and line, those read at their
/// calls too (module `percall`).
fn routines_of(code: &str, statements: &[Statement]) -> Vec<(String, u64)> {
    (statements.iter())
        .filter_map(|s| routine(&code[s.span.clone()]).map(|name| (name, s.line)))
        .collect()
}

/// Whether a statement of `statements` (of `code`) that is `read` switches configuration
/// monitoring.
fn switches_read(code: &str, statements: &[Statement], read: &[bool]) -> bool {
    (statements.iter().zip(read))
        .any(|(s, read)| *read && switching(code, std::slice::from_ref(s)).is_some())
}

/// The first statement of `statements` (of `code`) that switches configuration monitoring
/// (`ConfJ`, `ConfL`), if any.
fn switching<'s>(code: &str, statements: &'s [Statement]) -> Option<&'s Statement> {
    statements.iter().find(|s| {
        matches!(
            first_word(&code[s.span.clone()]).as_str(),
            "confj" | "confl"
        )
    })
}

/// The targets and motions left `found` by a call, added to `out` and `left`; a refusal left as
/// found where the context says.
fn keep(
    found: Result<(Vec<JointTarget>, Vec<Left>)>,
    context: &Context,
    (out, left): (&mut Vec<JointTarget>, &mut Vec<Left>),
) -> Result<()> {
    match found {
        Ok((t, l)) => {
            out.extend(t);
            left.extend(l);
            Ok(())
        }
        Err(e) => context.leave(left, e),
    }
}

/// A compact `IF cond instruction;`: its motion read where it is (a branch of one statement),
/// its call of a procedure of the module or the task as any call.
#[allow(clippy::too_many_arguments)]
fn compact_if(
    here: &Here,
    (code, body): (&str, &str),
    (data, conf): (&Data, &Conf),
    context: &Context,
    (out, left): (&mut Vec<JointTarget>, &mut Vec<Left>),
    flow: &mut flow::Flow,
    task: &mut Task,
    layout: &Layout,
) -> Result<()> {
    let s = here.statement;
    if flow::compact_instruction(body).is_none() {
        return Err(at(s.line, "IF: no instruction after its condition (a parenthesis, bracket or string left open?): the controller refuses the statement".into()));
    }
    if let Some((name, line, _)) = flow::in_compact_if(body, s.line, flow::is_jump) {
        let jump = format!("IF (line {}) {}", s.line, name.to_uppercase());
        flow.jump(&jump, line);
    }
    if let Some((name, line, at)) = flow::in_compact_if(body, s.line, flow::is_motion) {
        let inner = Statement {
            line,
            span: s.span.start + at..s.span.end,
        };
        let name = name.to_ascii_lowercase();
        return match moves(&inner, code, &name, data, conf) {
            Ok(found) => {
                out.extend(found);
                Ok(())
            }
            Err(e) => context.leave(left, e),
        };
    }
    if let Some((name, at)) = calls::in_compact_if(body) {
        let mut conf = conf.clone();
        let call = (name, &body[at + name.len()..]);
        let found = call_of(here, call, (data, &mut conf), context, task, layout);
        keep(found, context, (out, left))?;
    }
    Ok(())
}

/// The call of procedure `name` (its arguments `args`, up to the `;`) at `here`: nothing for a
/// routine of the module (read where it is); the targets of a `PROC` of the task's other modules
/// (module `called`), with the configuration monitoring `conf` in force (unknown after it where
/// that module switches it); a call refused where it runs between two motions (module `calls`).
fn call_of(
    here: &Here,
    (name, args): (&str, &str),
    (data, conf): (&Data, &mut Conf),
    context: &Context,
    task: &mut Task,
    layout: &Layout,
) -> Result<(Vec<JointTarget>, Vec<Left>)> {
    let line = here.statement.line;
    let key = name.to_ascii_lowercase();
    if name == "%" {
        return match here.place.between() {
            true => Err(at(line, "a late-bound call (%name%, CallByVar): the procedure it runs is named at run time, and may move the robot between the motions around it, off the file's path; call the procedure by its name".into())),
            false => Ok((Vec::new(), Vec::new())),
        };
    }
    if layout.per_call.contains(&key) {
        return super::percall::read(here, (name, args), (data, conf), (context, task), module);
    }
    if layout.routines.contains(&key) {
        return Ok((Vec::new(), Vec::new()));
    }
    let Some(&(file, text)) = task.procs.get(&key) else {
        return match here.place.between() {
            true => Err(at(line, format!("{name}: a call of a procedure neither this module nor the task's modules given declare (PROC {name}), between two motions: it may move the robot off the file's path; give the task's modules (--backup, Python backup=) holding it"))),
            false => Ok((Vec::new(), Vec::new())),
        };
    };
    let refuse = |why: String| at(line, format!("{name}: {why}"));
    if let Some(second) = task.twice.get(&key) {
        return Err(refuse(format!("PROC {name} is declared in {file} and in {second}: the controller does not load a task whose modules declare one routine twice; keep one")));
    }
    let link = format!("{}.{key}", crate::program::file_name(file));
    if task.chain.contains(&link) || task.chain.len() >= 16 {
        return Err(refuse(format!(
            "the procedure calls itself through {}; stiffid follows calls that end",
            task.chain.join(", ")
        )));
    }
    task.reads += 1;
    if task.reads > MAX_READS {
        return Err(refuse(format!("more than {MAX_READS} calls of the task's procedures read: stiffid reads each where it is called")));
    }
    crate::program::ends::check(text, crate::program::Dialect::Rapid)
        .map_err(|e| refuse(format!("{file}: {e}")))?;
    let header = calls::header(text, &key);
    let entry = Entry {
        name: key,
        bindings: Bindings::of(&header, (args, line, None), data),
        place: here.place,
        conf: conf.clone(),
        alone: false,
    };
    let before = (task.files.len(), task.total);
    let offset = match task.offsets.get(file) {
        Some(at) => *at,
        None => {
            task.offsets.insert(file.to_string(), task.total);
            task.total += text.len();
            task.files.push((file.to_string(), text.to_string()));
            before.1
        }
    };
    task.chain.push(link);
    let read = module(text, offset, Some(&entry), context, task);
    task.chain.pop();
    let within = |e: Error| match e {
        Error::Program { line: l, message } => refuse(format!("{} line {l}: {message}", file)),
        other => other,
    };
    let read = match read {
        Ok(r) if !(r.targets.is_empty() && r.left.is_empty()) => r,
        other => {
            // Nothing moves (or refused): the modules first read here are not written.
            for (f, _) in task.files.drain(before.0..) {
                task.offsets.remove(&f);
            }
            task.total = before.1;
            other.map_err(within)?
        }
    };
    if read.switches_conf {
        let why = format!("the call of {name} on line {line} may switch configuration monitoring ({file}), which stiffid does not follow out of it; set ConfJ and ConfL after the call");
        conf.0 = [Err(why.clone()), Err(why)];
    }
    let targets = (read.targets.into_iter())
        .map(|t| JointTarget {
            motion_at: t.motion_at.or(Some(offset)),
            ..t
        })
        .collect();
    let left = (read.left.into_iter())
        .map(|l| Left {
            line,
            why: format!("{name}: {file} line {}: {}", l.line, l.why),
            point: l.point,
        })
        .collect();
    Ok((targets, left))
}

/// The name (lower case) of the last routine of `routines`.
fn name_of(routines: &[(String, u64)]) -> String {
    routines
        .last()
        .map_or(String::new(), |(n, _)| n.to_ascii_lowercase())
}

/// Configuration monitoring at the start of the routine on `line`: on (the controller's
/// default, as at the program's start) in a routine the module does not call or a module that
/// never switches it (`switches` `None`); else the caller's, which the module does not say.
fn conf_at_start(switches: Option<&Statement>, line: u64) -> Conf {
    match switches {
        None => Conf([Ok(false), Ok(false)], Bound::new(), Values::new()),
        Some(s) => {
            let why = format!("the module switches configuration monitoring (line {}), and at the start of the routine on line {line} it is in the state its caller leaves, which the module does not say; set ConfJ and ConfL at the routine's start", s.line);
            Conf([Err(why.clone()), Err(why)], Bound::new(), Values::new())
        }
    }
}

/// Follows a header statement `first` (lower case) on `line` that opens, divides or closes a
/// branch or loop.
fn branches(first: &str, line: u64, paths: &mut Paths<Conf>, conf: &mut Conf) {
    let kind = match first {
        "if" => Some(Kind::Branches),
        "test" => Some(Kind::Cases),
        "while" | "for" => Some(Kind::Loop),
        _ => None,
    };
    match (kind, first) {
        (Some(kind), _) => paths.open((&first.to_ascii_uppercase(), line), conf, kind, 0),
        (None, "elseif" | "case") => paths.branch(conf, false),
        (None, "else" | "default") => paths.branch(conf, true),
        (None, "endif" | "endtest" | "endwhile" | "endfor") => _ = paths.close(conf),
        _ => {}
    }
}

/// The targets of the statement `s` (`first` its instruction), with configuration monitoring
/// `conf` in force: a `MoveL`, `MoveC` or `MoveJ` with it off follows the arm's configuration.
///
/// # Errors
/// Those of [`motion`]; a Cartesian motion where the file does not say whether monitoring is on.
fn moves(
    s: &Statement,
    code: &str,
    first: &str,
    data: &super::Data,
    conf: &Conf,
) -> Result<Vec<JointTarget>> {
    let mut found = motion(s, code, first, data)?;
    let first = super::as_move(first);
    let linear = matches!(first, "movel" | "movec");
    if found.is_empty() || !(linear || first == "movej") {
        return Ok(found);
    }
    match &conf.0[usize::from(linear)] {
        Err(why) => Err(at(s.line, why.clone())),
        Ok(false) => Ok(found),
        Ok(true) => {
            // Configuration monitoring off: the motion keeps the arm's configuration from the
            // posture before it, whatever its confdata says.
            for c in found.iter_mut().filter_map(|t| t.cartesian.as_deref_mut()) {
                c.follows = true;
            }
            Ok(found)
        }
    }
}

/// Refuses a jump of the routine just read (its motions from `first`) in a module that switches
/// configuration monitoring: after a jump the state in force is not the file's.
fn check_jumps(
    flow: &flow::Flow,
    routines: &[(String, u64)],
    first: Option<u64>,
    switches: Option<&Statement>,
) -> Result<()> {
    match (first, switches, routines.last()) {
        (Some(line), Some(_), Some((name, _))) => flow.check_jumps(&format!("PROC {name}"), line),
        _ => Ok(()),
    }
}
