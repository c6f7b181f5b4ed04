//! The text `stiffid compensate` prints: what was compensated, the error bound and what it is
//! made of, the free variables, what was written.

use super::Args;
use std::path::Path;
use stiffid::app::compensate::document::Document;
use stiffid::app::compensate::dynamics::OperationDynamics;
use stiffid::app::compensate::Report;
use stiffid::app::document::{finite, mm};
use stiffid::internal::common::words::{count, number};
use stiffid::internal::machining::program;
use stiffid::Setup;

/// What the error that remains is made of, and whether the program meets `--max-error-mm`.
fn made_of(b: &stiffid::app::compensate::budget::BudgetSummary) -> String {
    let parts: Vec<String> = (b.made_of.iter())
        .filter(|p| p.part != "left")
        .map(|p| match p.max_mm {
            Some(m) => format!(
                "{} {m:.4} mm (mean {:.4})",
                p.part.replace('_', " "),
                p.mean_mm.unwrap_or(m)
            ),
            None => format!("{} {}", p.part.replace('_', " "), b.no_value(p)),
        })
        .collect();
    let mut text = format!(
        "the error that remains at {}% is made of (largest along the path): {}\n",
        100.0 * b.level,
        parts.join(", ")
    );
    if let Some(m) = &b.meets {
        text += &format!(
            "meets {} mm at {}%: {}\n",
            number(m.max_error_mm),
            100.0 * m.level,
            if m.meets { "yes" } else { "no" }
        );
    }
    text
}

/// The text summary: what was compensated, the error bound, the free variables, what was
/// written.
pub(super) fn human(args: &Args, setup: &Setup, report: &Report, doc: &Document<'_>) -> String {
    let mut text = head(setup, report, doc);
    text += &bound(doc);
    text += &made_of(&doc.summary.budget);
    text += &free(doc);
    text += &written(args, report, doc);
    text
}

/// The summary's first lines: the points, the deflection, the residual, the intervals.
fn head(setup: &Setup, report: &Report, doc: &Document<'_>) -> String {
    let d = &doc.summary;
    let mut text = format!(
        "{} path points of {} compensated (setup {}, stiffness {}{})\n\
         TCP deflection under the path's wrench: largest {:.4} mm (line {}), mean {:.4} mm; largest tool rotation {:.4} mrad\n\
         compensated axis angles: residual at most {:.2e} um and {:.2e} urad (required: 0.1 um, 1 urad), at most {} Newton steps ({})\n",
        d.points,
        report.input,
        setup.name(),
        doc.stiffness,
        if report.compliance.covariance.is_some() { ", with its covariance: standard deviations in the CSV" } else { "" },
        mm(d.max_deflection),
        d.max_deflection_line,
        mm(d.mean_deflection),
        d.max_rotation * 1e3,
        d.max_residual_position * 1e6,
        d.max_residual_rotation * 1e6,
        d.max_iterations,
        d.stop_reason
    );
    if let Some(level) = report.prediction_level {
        text += &format!(
            "prediction intervals of the TCP deflection ({:.0}%, from the held-out residuals of the identification) in the CSV; the widest {}\n",
            100.0 * level,
            d.max_interval_width.and_then(|w| finite(mm(w)))
                .map_or("is unbounded (too few held-out residuals for the level)".into(), |w| format!("is {w:.4} mm wide"))
        );
    }
    text
}

/// The error bound's line.
fn bound(doc: &Document<'_>) -> String {
    let b = &doc.summary.budget;
    format!(
        "error bound at {}%: largest {} (line {}), mean {}{}{}\n",
        100.0 * b.level,
        b.max_bound_mm.map_or(
            format!(
                "infinite (a finite bound needs at least {} held-out calibration errors)",
                stiffid::internal::model::prediction::held_out_needed(b.level)
            ),
            |m| format!("{m:.4} mm")
        ),
        b.max_bound_line.unwrap_or(0),
        b.mean_bound_mm
            .map_or("infinite".into(), |m| format!("{m:.4} mm")),
        b.worst.first().map_or(String::new(), |w| format!(
            ", mostly {} there",
            w.dominant.replace('_', " ")
        )),
        match b.absent.is_empty() {
            true => String::new(),
            false => format!(
                " ({} absent, counted as 0)",
                b.absent.join(", ").replace('_', " ")
            ),
        }
    )
}

/// The free variables' lines: the tool axis, lead and tilt, the feasibility, the speeds, the
/// grid's refinement, the configurations.
fn free(doc: &Document<'_>) -> String {
    let (d, mut text) = (&doc.summary, String::new());
    let rotation = doc.free.iter().any(|f| f.variable == "tool-rotation");
    if let (Some(f), true, Some(minimise)) = (&d.free_tool_axis, rotation, doc.minimise) {
        let [lo, hi] = f.tool_rotation_range.map(f64::to_degrees);
        text += &format!(
            "free tool axis (minimising the {}): mean TCP deflection {:.4} mm before, {:.4} mm after ({:+.1}%), tool rotation within [{lo:.1}, {hi:.1}] deg\n",
            minimise,
            mm(f.mean_deflection_before),
            mm(f.mean_deflection_after),
            f.mean_change_pct,
        );
    }
    if let Some(l) = &d.free_lead_tilt {
        text += &format!(
            "lead and tilt: largest lead {:.2} deg, largest tilt {:.2} deg, largest lean {:.2} deg, mean lean {:.2} deg\n",
            l.max_lead.to_degrees(),
            l.max_tilt.to_degrees(),
            l.max_lean.to_degrees(),
            l.mean_lean.to_degrees()
        );
    }
    if let Some(f) = &doc.feasibility {
        text += &format!(
            "moved postures kept {:.1} deg from the joint limits, condition number at most {}, the cell's collisions {}: states removed {} (limit margin), {} (singularity), {} (collision); moves refused {} (axis speed)\n",
            f.margin_deg,
            number(f.max_condition),
            if f.collisions_checked { "checked" } else { "not checked" },
            f.states_removed_limit_margin,
            f.states_removed_singularity,
            f.states_removed_collision,
            f.moves_refused_speed,
        );
    }
    // Why the speeds were not checked matters where a free variable moves the axes.
    if doc.speed_limits.not_checked_because.is_none() || doc.feasibility.is_some() {
        text += &crate::commands::speed_line::line(doc.speed_limits);
    }
    if let Some(levels) = doc.refine.filter(|&l| l > 0) {
        text += &format!("the free variables' grid refined {levels} time(s) around the line chosen on it, each level halving every step\n");
    }
    if let Some(c) = &doc.configurations {
        text += &crate::commands::configuration_table::table(c);
    }
    text
}

/// The program and the files written.
fn written(args: &Args, report: &Report, doc: &Document<'_>) -> String {
    let (names, mut text) = (&report.names, String::new());
    if let Some(p) = &doc.program {
        text += &format!(
            "program ({}, process {}): {}, force on the tool up to {:.1} N (the process's and the tool's weight)\n",
            p.language,
            p.process,
            count(p.segments.len(), "segment"),
            p.max_force_n
        );
        for o in p.dynamics {
            text += &dynamics_line(o);
        }
    }
    for written in [&names.program_out, &names.out] {
        if !written.is_empty() {
            text += &format!("written: {written}\n");
        }
    }
    let dat = program::data_out(Path::new(&names.program_out));
    if let Some(dat) = dat.filter(|_| report.program.as_ref().is_some_and(|p| p.data.is_some())) {
        text += &format!(
            "written: {} beside it (its points and data)\n",
            dat.display()
        );
    }
    if let Some(p) = report
        .program
        .as_ref()
        .filter(|p| !p.subprograms.is_empty())
    {
        let (first, last) = (
            &p.subprograms[0].name,
            &p.subprograms[p.subprograms.len() - 1].name,
        );
        text += &format!(
            "written: {} beside it, {first} to {last}, which it calls in order\n",
            count(p.subprograms.len(), "sub-program")
        );
    }
    if let Some(dir) = &args.report {
        text += &format!("report: {}\n", Path::new(dir).join("report.html").display());
    }
    text
}

/// One operation's surge (drilling) or first frequency against its tooth passing (milling).
fn dynamics_line(o: &OperationDynamics) -> String {
    let mut line = format!("  {} '{}': ", o.kind, o.operation);
    if let (Some(v), Some(at)) = (o.max_surge_mm_s, o.max_surge_line) {
        let std = o
            .max_surge_std_mm_s
            .map_or(String::new(), |s| format!(" +- {s:.1}"));
        line += &format!(
            "{} exits, breakthrough surge up to {v:.1}{std} mm/s (line {at}, held mass {:.1} kg)",
            o.points,
            o.max_surge_effective_mass_kg.unwrap_or(f64::NAN)
        );
        if let Some(b) = o.max_surge_before_mm_s {
            line += &format!("; {b:.1} mm/s at the path's own tool rotation");
        }
    } else if let Some([lo, hi]) = o.first_frequency_hz {
        line += &format!("first natural frequency {lo:.1}-{hi:.1} Hz");
        if let (Some(t), Some(p), Some(k)) = (
            o.tooth_passing_hz,
            o.nearest_harmonic_pct,
            o.nearest_harmonic_order,
        ) {
            line += &format!(", tooth passing {t:.1} Hz (nearest: {p:.1}% from harmonic {k})");
        }
    } else {
        line += "no surge or frequency (a singular posture)";
    }
    line + "\n"
}
