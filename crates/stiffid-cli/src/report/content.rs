//! What the report says, in order, independent of the format: [`super::html`] and
//! [`super::markdown`] implement [`Writer`].

use super::figures::Figure;
use super::tables::{self, Table};
use stiffid::app::reproduce::document::{search_words, sentences};
use stiffid::app::reproduce::Report;
use stiffid::internal::design::study::paper_table4;
use stiffid::internal::view::Scene;

/// A report format.
pub trait Writer {
    /// A heading, level 1 (title) to 3.
    fn heading(&mut self, level: usize, text: &str);
    /// A paragraph. `code spans` in backticks are kept as code.
    fn paragraph(&mut self, text: &str);
    /// A bulleted list.
    fn list(&mut self, items: &[String]);
    /// A table.
    fn table(&mut self, table: &Table);
    /// A figure with its caption.
    fn figure(&mut self, figure: &Figure);
    /// The 3D scene (HTML: the viewer; other formats: the name of its `.glb` file, `glb`).
    fn scene(&mut self, scene: &Scene, glb: &str);
}

fn find<'a>(figures: &'a [Figure], name: &str) -> Option<&'a Figure> {
    figures.iter().find(|f| f.name == name)
}

/// Writes the whole report of `report`.
pub fn compose(report: &Report, figures: &[Figure], w: &mut dyn Writer) {
    let (study, f) = (&report.study, &report.findings);
    let s = &study.setup;
    w.heading(1, "Posture selection for joint stiffness identification: the simulation study of Zhang et al. (2021)");
    w.paragraph(&format!(
        "Reproduces Section IV-A of Zhang, Guo, Sun and Sun, \"Method of Postures Selection for Industrial Robot Joint Stiffness Identification\", IEEE Access 9 (2021), doi:10.1109/ACCESS.2021.3073671 (Figs. 5-8, Tables 3-4) on the setup `{}` ({}), and shows beside it what scale-free criteria searched globally achieve. {} groups of {} postures, {} Monte Carlo runs per group and noise level, seed {}; computed in {:.1} s.",
        s.name(), s.robot().name(), study.groups.len(), stiffid::internal::design::study::POSTURES, study.runs, study.seed, study.elapsed_s
    ));
    w.heading(2, "Findings");
    w.list(&sentences(f, study));
    w.table(&tables::groups(study));
    w.heading(
        2,
        "Average deviation rate against noise level (the paper's Fig. 8)",
    );
    if let Some(fig) = find(figures, "deviation_vs_noise") {
        w.figure(fig);
    }
    w.heading(
        2,
        &format!(
            "Deviation rates at noise level {} (the paper's Table 4)",
            study.validation_level + 1
        ),
    );
    if let Some(fig) = find(figures, "table4_level2") {
        w.figure(fig);
    }
    w.paragraph("The same numbers: mean ± standard deviation over the runs, [first-order prediction], %. The paper's Table 4 shows a single run; a mean over runs is what a reader can compare across seeds.");
    w.table(&tables::table4(study));
    if let Some(paper) = paper_table4(study) {
        w.paragraph("For reference, the paper's own Table 4 (one run, its own tool, rope anchor and start group, none of which the paper gives in full) beside this study's means. Single runs scatter by about their mean (the standard deviations above are close to the means), so only the orders of magnitude compare, and one cell (0.002%, the paper's Group 3, joint 3) can land near zero by chance.");
        w.table(&tables::paper_table4(study, paper));
    }
    w.heading(2, "Does the criterion predict accuracy?");
    w.paragraph("Every design criterion of every group (smaller is better) beside the group's measured average deviation rate. rho is Spearman's rank correlation between the criterion and the measured average deviation rate over the groups: +1 means the criterion ranks the groups exactly as their accuracy does.");
    w.table(&tables::criteria(study, f));
    if let Some(fig) = find(figures, "criteria_vs_deviation") {
        w.figure(fig);
    }
    w.heading(2, "The groups of postures (the paper's Figs. 5-7)");
    for (g, group) in study.groups.iter().enumerate() {
        w.heading(3, &group.title);
        w.paragraph(&format!(
            "{}. Postures in `{}.csv`.",
            search_words(&group.origin, study.seed),
            group.name
        ));
        w.table(&tables::postures(study, g));
        if let Some(fig) = find(figures, &format!("postures_{}", group.name)) {
            w.figure(fig);
        }
    }
    if !study.trials.is_empty() {
        w.heading(2, "Does the paper's result depend on the start group?");
        w.paragraph(&format!(
            "The paper searches locally from one start group. The same two local searches (`classical`, `zhang2021`) from {} seeded start groups, each group judged by its first-order predicted average deviation rate (mean over joints and the {} noise levels, %; the Findings say how closely it follows the Monte Carlo means). Seed {} is Group 1 above.",
            study.trials.len(),
            s.noise().levels.len(),
            study.seed
        ));
        w.table(&tables::trials(study));
    }
    w.heading(2, "Validation postures (the paper's Table 5)");
    w.paragraph(&format!(
        "Deflection of the measuring points at the setup's test postures under the rope-mass load, with the true stiffness, and the error of the deflection predicted with each group's mean identified stiffness at noise level {} (largest over the measuring points, Eq. 22). Averaged over {} runs the identification is nearly unbiased, so these errors are small for every group; the error of a single experiment is what `test_pose_mm` predicts.",
        study.validation_level + 1,
        study.runs
    ));
    w.table(&tables::validation(study));
    w.heading(2, "Setup and method");
    w.paragraph(&format!(
        "{} The paper does not give every number (its tool drawing, Fig. 3, is not in the text): the setup's own choices for the tool points, the rope anchor and the characteristic length, and why, are in `stiffid setups show {}` (or the setup file).",
        s.description(), s.name()
    ));
    w.table(&tables::setup(study));
    w.list(&[
        "Load: a rope pulls the loading point toward the anchor with the load G, F = G (P2 - P1)/|P2 - P1|, no moment (Section IV-A).".into(),
        "Simulation: exact displacements of every measuring point with the true stiffness, white Gaussian noise of variance sigma^2 m on every coordinate (Table 3), compliances by least squares with the QR factor of the observation matrix (once per group), deviation rate |k_id - k_true| / k_true per joint. Every run has its own seeded noise generator: the same seed gives the same numbers whatever the thread count.".into(),
        "Groups 2 and 3 are local SQP searches (SLSQP, the paper's fmincon) from Group 1 within the bounds; the further groups are global searches (many SQP searches from seeded Latin-hypercube starts, best kept), which the paper names as future work.".into(),
        "Files: summary.json (everything, machine-readable), deviation_rates.csv (every group, level and joint), one postures CSV per group, figures/ (SVG and PNG).".into(),
    ]);
}
