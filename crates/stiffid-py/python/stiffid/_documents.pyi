"""The JSON documents of stiffid as TypedDicts, generated from the JSON Schemas in docs/schemas by
crates/stiffid-py/tools/stubs.py (do not edit; tests/test_stubs.py keeps them equal)."""

from typing import Any, Literal, Optional, TypedDict, Union

from typing_extensions import NotRequired


# calibrate-cell: docs/schemas/calibrate-cell.schema.json

CalibrateCellDocument = TypedDict("CalibrateCellDocument", {
    "absolute_error_rms_mm": float,
    "data": str,
    "fragment": str,
    "iterations": int,
    "kind": Literal["calibrate-cell"],
    "noise_std_mm": float,
    "points": list[CalibrateCellToolPoint],
    "readings": int,
    "rotation_std_deg": list[float],
    "rpy_deg": list[float],
    "setup": str,
    "stop_reason": CalibrateCellStop,
    "translation_std_mm": list[float],
    "xyz_mm": list[float],
})

CalibrateCellStop = Literal["converged", "stalled", "damping-exhausted", "iteration-limit"]

CalibrateCellToolPoint = TypedDict("CalibrateCellToolPoint", {
    "fitted_mm": list[float],
    "point": int,
    "setup_mm": list[float],
    "shift_mm": list[float],
    "std_mm": Optional[list[float]],
})

# calibrate: docs/schemas/calibrate.schema.json

CalibrateDocument = TypedDict("CalibrateDocument", {
    "check": Optional[CalibrateCheckDocument],
    "condition": Optional[float],
    "correlations": list[CalibrateCorrelation],
    "cross_validation": Optional[CalibrateValidationDocument],
    "data": str,
    "errors": list[CalibrateBeforeAfter],
    "fragment": str,
    "geometry": str,
    "gravity": str,
    "gravity_prior_mrad": Optional[float],
    "held": list[str],
    "iterations": int,
    "kind": Literal["calibrate"],
    "ladder": Optional[CalibrateLadderDocument],
    "maps": CalibrateMapsDocument,
    "measured_in": str,
    "merged": list[CalibrateMerged],
    "noise_ratio": Optional[float],
    "noise_std_mm": float,
    "nominal_rms_mm": float,
    "parameters": list[CalibrateParameter],
    "postures": list[CalibrateStance],
    "rank": int,
    "readings": int,
    "residual_rms_mm": float,
    "robot_file": Optional[str],
    "robot_file_error": Optional[str],
    "setup": str,
    "stiffness_file": Optional[CalibrateStiffnessFile],
    "stiffness_file_error": Optional[str],
    "stop_reason": CalibrateStop,
    "tcp_mm": NotRequired[Optional[list[float]]],
    "urdf": Optional[str],
    "urdf_error": Optional[str],
    "validation": Optional[CalibrateValidationDocument],
    "warnings": list[CalibrateWarning],
})

CalibrateBeforeAfter = TypedDict("CalibrateBeforeAfter", {
    "after_mm": list[float],
    "after_norm_mm": float,
    "before_mm": list[float],
    "before_norm_mm": float,
    "point": int,
    "point_name": str,
    "posture": str,
    "set": str,
})

CalibrateCheckDocument = TypedDict("CalibrateCheckDocument", {
    "allowed": int,
    "bound_mm": float,
    "drifted": bool,
    "errors": list[CalibrateCheckedReading],
    "held_out": int,
    "level": float,
    "outside": int,
    "readings": int,
    "share_outside": float,
    "source": str,
})

CalibrateCheckedReading = TypedDict("CalibrateCheckedReading", {
    "error_mm": float,
    "outside": bool,
    "point": int,
    "point_name": str,
    "posture": str,
})

CalibrateCorrelation = TypedDict("CalibrateCorrelation", {
    "a": str,
    "b": str,
    "rho": float,
})

CalibrateFileKind = Literal["stiffness", "identify-drives", "identify-springs"]

CalibrateFoldSection = TypedDict("CalibrateFoldSection", {
    "compliance_si": list[float],
    "postures": list[str],
    "scores": list[float],
})

CalibrateFormLaw = Literal["linear", "lost-motion", "load-dependent"]

CalibrateFormModelSection = TypedDict("CalibrateFormModelSection", {
    "compliance_si": list[list[float]],
    "springs": list[str],
})

CalibrateFormSpring = TypedDict("CalibrateFormSpring", {
    "axis": list[float],
    "kind": CalibrateKind,
    "law": CalibrateFormLaw,
    "link": int,
    "name": str,
    "point_mm": list[float],
})

CalibrateGravitySection = TypedDict("CalibrateGravitySection", {
    "model": str,
    "terms": list[CalibrateGravityTerm],
})

CalibrateGravityTerm = TypedDict("CalibrateGravityTerm", {
    "name": str,
    "value_si": float,
})

CalibrateIntervalsDocument = TypedDict("CalibrateIntervalsDocument", {
    "assumption": Optional[str],
    "coordinates": int,
    "coverage": float,
    "coverage_pct": float,
    "covered": int,
    "folds": int,
    "from_fit": int,
    "held_out_needed": int,
    "level": float,
    "median_width_mm": Optional[float],
    "method": str,
})

CalibrateKind = Literal["rotation", "translation"]

CalibrateLadderDocument = TypedDict("CalibrateLadderDocument", {
    "best": Optional[int],
    "chosen": int,
    "folds": int,
    "region_lower_deg": list[float],
    "region_upper_deg": list[float],
    "rungs": list[CalibrateRungDocument],
    "why": str,
})

CalibrateMapTried = TypedDict("CalibrateMapTried", {
    "kept": bool,
    "maps": str,
    "ridge": float,
    "rms_mm": float,
})

CalibrateMapsDocument = TypedDict("CalibrateMapsDocument", {
    "asked": str,
    "chosen": str,
    "inner_none_rms_mm": Optional[float],
    "inner_rms_mm": Optional[float],
    "nested": Optional[CalibrateMapsNested],
    "postures": int,
    "ridge": Optional[float],
    "skipped": Optional[str],
    "tried": list[CalibrateMapTried],
})

CalibrateMapsNested = TypedDict("CalibrateMapsNested", {
    "choices": list[str],
    "folds": int,
    "none_rms_mm": float,
    "rms_mm": float,
})

CalibrateMerged = TypedDict("CalibrateMerged", {
    "into": list[str],
    "name": str,
    "reason": str,
})

CalibrateModelFormSection = TypedDict("CalibrateModelFormSection", {
    "models": list[CalibrateFormModelSection],
    "recommended": NotRequired[Optional[CalibrateFormModelSection]],
    "resamples": int,
    "seed": int,
    "springs": list[CalibrateFormSpring],
})

CalibrateOutsideRange = TypedDict("CalibrateOutsideRange", {
    "distance_deg": float,
    "joints": list[int],
})

CalibrateParameter = TypedDict("CalibrateParameter", {
    "identified": bool,
    "inseparable_from": list[str],
    "kind": str,
    "name": str,
    "nominal": float,
    "robot_file_si": Optional[float],
    "sd": Optional[float],
    "unit": str,
    "value": float,
})

CalibrateParameterKind = Literal["drive", "rotation", "translation", "lost-motion", "load-dependent"]

CalibrateParameterStiffness = TypedDict("CalibrateParameterStiffness", {
    "ci95": NotRequired[Optional[list[Optional[float]]]],
    "identified": NotRequired[Optional[bool]],
    "kind": CalibrateParameterKind,
    "name": str,
    "stiffness": Optional[float],
    "unit": str,
})

CalibratePointError = TypedDict("CalibratePointError", {
    "error_mm": list[float],
    "error_norm_mm": float,
    "interval_holds": Optional[bool],
    "interval_mm": Optional[list[list[Optional[float]]]],
    "outside_range": Optional[CalibrateOutsideRange],
    "point": int,
    "point_name": str,
    "posture": str,
})

CalibratePredictionSection = TypedDict("CalibratePredictionSection", {
    "deflection_scores": Optional[list[float]],
    "folds": list[CalibrateFoldSection],
    "method": str,
    "model_error_pct": Optional[float],
    "noise_floor_mm": float,
    "postures": int,
    "score_q95": Optional[float],
    "score_q95_pct": Optional[float],
})

CalibrateRegionSection = TypedDict("CalibrateRegionSection", {
    "lower_deg": list[float],
    "margin_deg": float,
    "postures": int,
    "upper_deg": list[float],
})

CalibrateRungDocument = TypedDict("CalibrateRungDocument", {
    "gravity": str,
    "held_out_rms_mm": Optional[float],
    "maps": bool,
    "skipped": Optional[str],
    "workspace_sd_mm": Optional[float],
})

CalibrateStance = TypedDict("CalibrateStance", {
    "label": str,
    "q_deg": list[float],
})

CalibrateStiffnessFile = TypedDict("CalibrateStiffnessFile", {
    "compliance_covariance_rad2_per_nm2": NotRequired[Optional[list[list[float]]]],
    "compliance_covariance_si": NotRequired[Optional[list[list[float]]]],
    "fitted": NotRequired[Optional[list[bool]]],
    "gravity": NotRequired[Optional[CalibrateGravitySection]],
    "kind": NotRequired[Optional[CalibrateFileKind]],
    "model_form": NotRequired[Optional[CalibrateModelFormSection]],
    "parameters": NotRequired[Optional[list[CalibrateParameterStiffness]]],
    "prediction": NotRequired[Optional[CalibratePredictionSection]],
    "region": NotRequired[Optional[CalibrateRegionSection]],
    "stiffness_nm_per_rad": NotRequired[Optional[list[float]]],
    "unidentifiable": NotRequired[Optional[list[str]]],
})

CalibrateStop = Literal["converged", "stalled", "damping-exhausted", "iteration-limit"]

CalibrateValidationDocument = TypedDict("CalibrateValidationDocument", {
    "beyond_range_readings": int,
    "beyond_range_rms_mm": Optional[float],
    "coverage": Optional[float],
    "data": str,
    "errors": list[CalibratePointError],
    "intervals": Optional[CalibrateIntervalsDocument],
    "max_mm": float,
    "nominal_rms_mm": float,
    "rms_mm": float,
    "within_range_rms_mm": Optional[float],
})

CalibrateWarning = TypedDict("CalibrateWarning", {
    "kind": CalibrateWarningKind,
    "message": str,
})

CalibrateWarningKind = Literal["all-negative", "negative", "rigid", "units", "plausibility", "load-steps", "no-force", "unidentifiable", "meshes", "misfit", "feed", "near-postures", "old-field", "not-converged", "masses", "chatter", "configuration", "left-out", "extrapolation", "speed", "calibrated", "model-form", "encoding"]

# compensate: docs/schemas/compensate.schema.json

CompensateDocument = TypedDict("CompensateDocument", {
    "configurations": Optional[CompensateConfigurationsDocument],
    "feasibility": Optional[CompensateFeasibility],
    "free": list[CompensateFreeVariable],
    "generator": str,
    "has_covariance": bool,
    "kind": Literal["compensate"],
    "minimise": Optional[str],
    "model_ranking": Optional[CompensateRankingDocument],
    "objective": Optional[str],
    "out": str,
    "parameters": list[CompensateParameterStiffness],
    "path": str,
    "points": list[CompensateRow],
    "prediction_level": Optional[float],
    "program": Optional[CompensateProgram],
    "refine": Optional[int],
    "region": Optional[CompensateRegionSection],
    "setup": str,
    "speed_limits": CompensateSpeedLimits,
    "springs": CompensateCoordinates,
    "stiffness": str,
    "stiffness_nm_per_rad": list[float],
    "summary": CompensateSummaryDocument,
    "warnings": list[CompensateWarning],
})

CompensateAxisSpeed = TypedDict("CompensateAxisSpeed", {
    "axis": str,
    "chosen_highest_share": Optional[float],
    "chosen_line": Optional[int],
    "chosen_point": Optional[int],
    "max_speed_deg_s": Optional[float],
    "max_speed_mm_s": Optional[float],
    "own_highest_share": Optional[float],
    "own_line": Optional[int],
    "own_point": Optional[int],
})

CompensateBudgetSummary = TypedDict("CompensateBudgetSummary", {
    "absent": list[str],
    "level": float,
    "made_of": list[CompensatePartSummary],
    "max_bound_before_mm": Optional[float],
    "max_bound_line": Optional[int],
    "max_bound_mm": Optional[float],
    "mean_bound_mm": Optional[float],
    "meets": Optional[CompensateMeets],
    "worst": list[CompensateWorstPoint],
})

CompensateConfigurationRow = TypedDict("CompensateConfigurationRow", {
    "chosen": bool,
    "configuration_data": dict[str, str],
    "failed_because": Optional[str],
    "failed_line": Optional[int],
    "feasible": bool,
    "max_mm": Optional[float],
    "name": str,
    "objective_mm": Optional[float],
    "own": bool,
    "q_first_deg": list[float],
    "sum_mm": Optional[float],
})

CompensateConfigurationsDocument = TypedDict("CompensateConfigurationsDocument", {
    "aggregate": str,
    "chosen": str,
    "configurations": list[CompensateConfigurationRow],
    "objective": str,
    "objective_mm": Optional[float],
    "own": Optional[str],
    "per": str,
    "runs": list[CompensateRunRow],
})

CompensateCoordinates = Literal["axis", "kinematic"]

CompensateFeasibility = TypedDict("CompensateFeasibility", {
    "collisions_checked": bool,
    "margin_deg": float,
    "max_condition": float,
    "moves_refused_speed": int,
    "states_removed_collision": int,
    "states_removed_limit_margin": int,
    "states_removed_singularity": int,
})

CompensateFreeSummary = TypedDict("CompensateFreeSummary", {
    "mean_change_pct": float,
    "mean_deflection_after_mm": float,
    "mean_deflection_before_mm": float,
    "sum_deflection_after_mm": float,
    "sum_deflection_before_mm": float,
    "tool_rotation_range_deg": list[float],
})

CompensateFreeVariable = TypedDict("CompensateFreeVariable", {
    "per": Optional[str],
    "range": Optional[float],
    "step": Optional[float],
    "unit": Optional[str],
    "variable": str,
})

CompensateLeanSummary = TypedDict("CompensateLeanSummary", {
    "max_lead_deg": float,
    "max_lean_deg": float,
    "max_tilt_deg": float,
    "mean_lean_deg": float,
})

CompensateMeets = TypedDict("CompensateMeets", {
    "level": float,
    "max_error_mm": float,
    "meets": bool,
})

CompensateOperationDynamics = TypedDict("CompensateOperationDynamics", {
    "first_frequency_hz": Optional[list[float]],
    "kind": str,
    "max_surge_before_mm_s": Optional[float],
    "max_surge_effective_mass_kg": Optional[float],
    "max_surge_line": Optional[int],
    "max_surge_mm_s": Optional[float],
    "max_surge_std_mm_s": Optional[float],
    "nearest_harmonic_line": Optional[int],
    "nearest_harmonic_order": Optional[int],
    "nearest_harmonic_pct": Optional[float],
    "operation": str,
    "points": int,
    "tooth_passing_hz": Optional[float],
})

CompensateParameterKind = Literal["drive", "rotation", "translation", "lost-motion", "load-dependent"]

CompensateParameterStiffness = TypedDict("CompensateParameterStiffness", {
    "ci95": NotRequired[Optional[list[Optional[float]]]],
    "identified": NotRequired[Optional[bool]],
    "kind": CompensateParameterKind,
    "name": str,
    "stiffness": Optional[float],
    "unit": str,
})

CompensatePartSummary = TypedDict("CompensatePartSummary", {
    "max_mm": Optional[float],
    "mean_mm": Optional[float],
    "part": str,
})

CompensateProgram = TypedDict("CompensateProgram", {
    "dynamics": list[CompensateOperationDynamics],
    "language": str,
    "max_force_n": float,
    "out": str,
    "output_language": str,
    "process": str,
    "segments": list[CompensateSegmentDocument],
    "subprograms": list[str],
})

CompensateRankedPoint = TypedDict("CompensateRankedPoint", {
    "deflection_mm": float,
    "line": int,
    "rank": float,
    "recommended_deflection_mm": float,
    "recommended_rank": float,
})

CompensateRankingDocument = TypedDict("CompensateRankingDocument", {
    "agree": bool,
    "largest_rank_differences": list[CompensateRankedPoint],
    "points": int,
    "recommended_springs": list[str],
    "rho": Optional[float],
    "threshold_rho": float,
})

CompensateRegionSection = TypedDict("CompensateRegionSection", {
    "lower_deg": list[float],
    "margin_deg": float,
    "postures": int,
    "upper_deg": list[float],
})

CompensateRow = TypedDict("CompensateRow", {
    "bound_before_mm": Optional[float],
    "bound_calibration_mm": Optional[float],
    "bound_compensation_mm": Optional[float],
    "bound_force_mm": Optional[float],
    "bound_left_mm": Optional[float],
    "bound_mm": Optional[float],
    "bound_model_form_mm": Optional[float],
    "d_norm_before_mm": Optional[float],
    "d_norm_mm": float,
    "drx_mrad": float,
    "drx_std_mrad": Optional[float],
    "dry_mrad": float,
    "dry_std_mrad": Optional[float],
    "drz_mrad": float,
    "drz_std_mrad": Optional[float],
    "dx_lower_mm": Optional[float],
    "dx_mm": float,
    "dx_std_mm": Optional[float],
    "dx_upper_mm": Optional[float],
    "dy_lower_mm": Optional[float],
    "dy_mm": float,
    "dy_std_mm": Optional[float],
    "dy_upper_mm": Optional[float],
    "dz_lower_mm": Optional[float],
    "dz_mm": float,
    "dz_std_mm": Optional[float],
    "dz_upper_mm": Optional[float],
    "effective_mass_kg": Optional[float],
    "extrapolates": Optional[float],
    "first_frequency_hz": Optional[float],
    "fx_base_n": float,
    "fy_base_n": float,
    "fz_base_n": float,
    "iterations": float,
    "lead_deg": float,
    "line": float,
    "mx_base_nm": float,
    "my_base_nm": float,
    "mz_base_nm": float,
    "point": float,
    "q1_deg": float,
    "q2_deg": float,
    "q3_deg": float,
    "q4_deg": float,
    "q5_deg": float,
    "q6_deg": float,
    "qc1_deg": float,
    "qc2_deg": float,
    "qc3_deg": float,
    "qc4_deg": float,
    "qc5_deg": float,
    "qc6_deg": float,
    "residual_um": float,
    "residual_urad": float,
    "rx_deg": float,
    "ry_deg": float,
    "rz_deg": float,
    "surge_before_mm_s": Optional[float],
    "surge_mm_s": Optional[float],
    "surge_std_mm_s": Optional[float],
    "tilt_deg": float,
    "tool_rotation_deg": float,
    "tooth_passing_hz": Optional[float],
    "x_mm": float,
    "y_mm": float,
    "z_mm": float,
})

CompensateRunRow = TypedDict("CompensateRunRow", {
    "chosen": str,
    "chosen_own": bool,
    "configuration_data": dict[str, str],
    "feasible": int,
    "first_line": int,
    "found": int,
    "last_line": int,
    "max_mm": Optional[float],
    "objective_mm": Optional[float],
    "own": Optional[str],
    "own_objective_mm": Optional[float],
    "points": int,
    "q_first_deg": list[float],
    "run": int,
    "sum_mm": Optional[float],
})

CompensateScenePart = TypedDict("CompensateScenePart", {
    "path_error": str,
    "path_mm": list[list[float]],
    "postures": list[CompensateStance],
})

CompensateSegmentDocument = TypedDict("CompensateSegmentDocument", {
    "deflection_after_mm": float,
    "deflection_before_mm": float,
    "deflection_std_mm": Optional[float],
    "force_n": float,
    "line": int,
    "operation": Optional[str],
    "points": int,
})

CompensateSpeedLimits = TypedDict("CompensateSpeedLimits", {
    "axes": list[CompensateAxisSpeed],
    "checked": bool,
    "moves_not_read": int,
    "not_checked_because": Optional[str],
})

CompensateStance = TypedDict("CompensateStance", {
    "label": str,
    "q_deg": list[float],
})

CompensateStop = Literal["converged", "stalled", "damping-exhausted", "iteration-limit"]

CompensateSummaryDocument = TypedDict("CompensateSummaryDocument", {
    "budget": CompensateBudgetSummary,
    "extrapolated": Optional[int],
    "free_lead_tilt": Optional[CompensateLeanSummary],
    "free_tool_axis": Optional[CompensateFreeSummary],
    "max_deflection_line": int,
    "max_deflection_mm": float,
    "max_interval_width_mm": Optional[float],
    "max_iterations": int,
    "max_remaining_error_mm": Optional[float],
    "max_residual_um": float,
    "max_residual_urad": float,
    "max_rotation_mrad": float,
    "mean_deflection_mm": float,
    "not_converged": int,
    "points": int,
    "scene": CompensateScenePart,
    "stop_reason": CompensateStop,
})

CompensateWarning = TypedDict("CompensateWarning", {
    "kind": CompensateWarningKind,
    "message": str,
})

CompensateWarningKind = Literal["all-negative", "negative", "rigid", "units", "plausibility", "load-steps", "no-force", "unidentifiable", "meshes", "misfit", "feed", "near-postures", "old-field", "not-converged", "masses", "chatter", "configuration", "left-out", "extrapolation", "speed", "calibrated", "model-form", "encoding"]

CompensateWorstPoint = TypedDict("CompensateWorstPoint", {
    "bound_mm": Optional[float],
    "dominant": str,
    "dominant_mm": Optional[float],
    "line": int,
})

# evaluate: docs/schemas/evaluate.schema.json

EvaluateDocument = TypedDict("EvaluateDocument", {
    "calibration": NotRequired[Optional[EvaluateCalibrationDoc]],
    "candidates": NotRequired[Optional[EvaluateCandidatesDoc]],
    "classical": Optional[float],
    "cond_psi": Optional[float],
    "d_optimal": Optional[float],
    "feasibility": list[EvaluatePosture],
    "infinite": list[EvaluateInfiniteCriterion],
    "kind": Literal["evaluate"],
    "parameters": list[EvaluateParameter],
    "predicted_deviation_pct": Optional[list[list[Optional[float]]]],
    "relative_a": Optional[float],
    "relative_std": Optional[list[Optional[float]]],
    "scaled_cond": Optional[float],
    "test_pose_mm": Optional[float],
    "unidentifiable": list[str],
    "zhang2021": Optional[float],
})

EvaluateCalibrationDoc = TypedDict("EvaluateCalibrationDoc", {
    "criterion": str,
    "d_optimality_mm2": float,
    "geometry": str,
    "gravity": str,
    "o1_mm": float,
    "o3_mm": float,
    "o4_mm": float,
    "o5_mm": float,
    "parameters": int,
    "predicted_rms_mm": Optional[float],
})

EvaluateCandidateDoc = TypedDict("EvaluateCandidateDoc", {
    "family": str,
    "identified": bool,
    "kind": str,
    "name": str,
    "needs_load_steps": bool,
    "separation": float,
    "unidentifiable": list[str],
})

EvaluateCandidatesDoc = TypedDict("EvaluateCandidatesDoc", {
    "candidates": list[EvaluateCandidateDoc],
    "designable": list[str],
    "dropped": list[EvaluateDroppedDoc],
    "load_levels": int,
    "nonlinear_separation": Optional[str],
    "not_designable": list[EvaluateDroppedDoc],
    "separable": list[str],
    "together": bool,
    "together_unidentifiable": list[str],
})

EvaluateDroppedDoc = TypedDict("EvaluateDroppedDoc", {
    "name": str,
    "reason": str,
})

EvaluateInfinite = Literal["singular", "not-separable", "overflow"]

EvaluateInfiniteCriterion = TypedDict("EvaluateInfiniteCriterion", {
    "criterion": str,
    "reason": EvaluateInfinite,
})

EvaluateParameter = TypedDict("EvaluateParameter", {
    "identified": bool,
    "name": str,
    "predicted_deviation_pct": Optional[float],
    "unit": str,
})

EvaluatePosture = TypedDict("EvaluatePosture", {
    "checks": list[str],
    "feasible": bool,
    "min_clearance_mm": Optional[float],
    "min_margin_check": Optional[str],
    "min_margin_mm": Optional[float],
    "posture": int,
    "violations": list[EvaluateViolation],
})

EvaluateViolation = TypedDict("EvaluateViolation", {
    "between": list[str],
    "check": str,
    "margin_deg": Optional[float],
    "margin_mm": Optional[float],
})

# force: docs/schemas/force.schema.json

ForceDocument = TypedDict("ForceDocument", {
    "kind": Literal["force"],
    "operations": list[ForceOperationForce],
    "peak_resolution_deg": Optional[float],
    "process": str,
})

ForceOperationForce = TypedDict("ForceOperationForce", {
    "kind": str,
    "mean_force_n": list[float],
    "mean_moment_nm": list[float],
    "name": str,
    "peak_force_n": NotRequired[Optional[list[float]]],
})

# identify: docs/schemas/identify.schema.json

IdentifyDocument = Union[IdentifyDrivesDocument, IdentifySpringsDocument, IdentifyComparisonDocument]

IdentifyBootstrapDoc = TypedDict("IdentifyBootstrapDoc", {
    "parameters": list[IdentifySpreadDoc],
    "recommended_share": float,
    "resamples": int,
    "seed": int,
    "unidentified": int,
})

IdentifyChosenDoc = TypedDict("IdentifyChosenDoc", {
    "folds": int,
    "name": str,
})

IdentifyCoordinates = Literal["axis", "kinematic"]

IdentifyCrossValidation = TypedDict("IdentifyCrossValidation", {
    "explained": float,
    "explained_pct": float,
    "explained_std_error": float,
    "explained_std_error_pct": float,
    "folds": int,
    "influential_postures": list[IdentifyInfluential],
    "per_fold": list[IdentifyFold],
    "rms_delta_b_mm": float,
    "rms_measured_mm": float,
    "stiffness_max_nm_per_rad": list[Optional[float]],
    "stiffness_mean_nm_per_rad": list[Optional[float]],
    "stiffness_min_nm_per_rad": list[Optional[float]],
    "stiffness_std_nm_per_rad": list[Optional[float]],
    "stiffness_std_pct": list[Optional[float]],
})

IdentifyCrossValidationDoc = TypedDict("IdentifyCrossValidationDoc", {
    "explained": float,
    "explained_pct": float,
    "explained_std_error": float,
    "explained_std_error_pct": float,
    "folds": int,
    "per_fold": list[IdentifyFoldDoc],
    "rms_delta_b_mm": float,
    "rms_measured_mm": float,
    "spread": list[IdentifySpread],
})

IdentifyDroppedDoc = TypedDict("IdentifyDroppedDoc", {
    "name": str,
    "reason": str,
})

IdentifyFitDoc = TypedDict("IdentifyFitDoc", {
    "compliance_covariance_si": Optional[list[list[float]]],
    "degrees_of_freedom": int,
    "model_check": Optional[IdentifyVerdict],
    "noise_ratio": Optional[float],
    "parameters": list[IdentifyParameterDoc],
    "rank": int,
    "residual_rms_mm": float,
    "scaled_cond": Optional[float],
    "unidentifiable": list[str],
})

IdentifyFold = TypedDict("IdentifyFold", {
    "delta_b_mm": list[float],
    "postures": list[str],
    "rms_delta_b_mm": float,
    "stiffness_nm_per_rad": list[Optional[float]],
})

IdentifyFoldDoc = TypedDict("IdentifyFoldDoc", {
    "delta_b_mm": list[float],
    "influential": list[str],
    "postures": list[str],
    "rms_delta_b_mm": float,
    "stiffness": list[Optional[float]],
})

IdentifyFoldSection = TypedDict("IdentifyFoldSection", {
    "compliance_si": list[float],
    "postures": list[str],
    "scores": list[float],
})

IdentifyFormLaw = Literal["linear", "lost-motion", "load-dependent"]

IdentifyFormModelSection = TypedDict("IdentifyFormModelSection", {
    "compliance_si": list[list[float]],
    "springs": list[str],
})

IdentifyFormSpring = TypedDict("IdentifyFormSpring", {
    "axis": list[float],
    "kind": IdentifyKind,
    "law": IdentifyFormLaw,
    "link": int,
    "name": str,
    "point_mm": list[float],
})

IdentifyInfluential = TypedDict("IdentifyInfluential", {
    "joints": list[int],
    "postures": list[str],
})

IdentifyIntervals = TypedDict("IdentifyIntervals", {
    "ci95_from_compliance_nm_per_rad": list[list[Optional[float]]],
    "ci95_nm_per_rad": list[list[Optional[float]]],
    "compliance_ci95_rad_per_nm": list[list[float]],
    "compliance_std_error_rad_per_nm": list[float],
    "quantile": float,
    "std_error_nm_per_rad": list[Optional[float]],
    "std_error_pct": list[Optional[float]],
})

IdentifyKind = Literal["rotation", "translation"]

IdentifyLoadStep = TypedDict("IdentifyLoadStep", {
    "hysteresis_flagged": bool,
    "hysteresis_mm": Optional[float],
    "hysteresis_p_value": Optional[float],
    "levels": int,
    "linearity_p_value": Optional[float],
    "nonlinear": bool,
    "offset_flagged": bool,
    "offset_p_value": Optional[float],
    "posture": str,
    "r_squared": Optional[float],
    "readings": int,
    "slope_mm_per_kn": Optional[float],
    "zero_load_offset_mm": Optional[float],
})

IdentifyModelDoc = TypedDict("IdentifyModelDoc", {
    "added": Optional[str],
    "aic": Optional[float],
    "bic": Optional[float],
    "held_out_explained": Optional[float],
    "held_out_explained_std_error": Optional[float],
    "held_out_mse_std_error_mm2": Optional[float],
    "held_out_rms_delta_b_mm": Optional[float],
    "identified": bool,
    "in_sample_explained": float,
    "model_check": Optional[IdentifyVerdict],
    "noise_ratio": Optional[float],
    "parameters": int,
    "physical": bool,
    "recommended": bool,
    "springs": list[str],
    "stiffness": list[IdentifyParameterDoc],
})

IdentifyModelFormSection = TypedDict("IdentifyModelFormSection", {
    "models": list[IdentifyFormModelSection],
    "recommended": NotRequired[Optional[IdentifyFormModelSection]],
    "resamples": int,
    "seed": int,
    "springs": list[IdentifyFormSpring],
})

IdentifyNestedDoc = TypedDict("IdentifyNestedDoc", {
    "chosen": list[IdentifyChosenDoc],
    "held_out_explained": float,
    "held_out_explained_std_error": float,
    "parameters": list[int],
    "rms_delta_b_mm": float,
})

IdentifyParameterDoc = TypedDict("IdentifyParameterDoc", {
    "ci95": Optional[list[Optional[float]]],
    "identified": bool,
    "kind": IdentifyParameterKind,
    "name": str,
    "stiffness": Optional[float],
    "unit": str,
})

IdentifyParameterKind = Literal["drive", "rotation", "translation", "lost-motion", "load-dependent"]

IdentifyParameterStiffness = TypedDict("IdentifyParameterStiffness", {
    "ci95": NotRequired[Optional[list[Optional[float]]]],
    "identified": NotRequired[Optional[bool]],
    "kind": IdentifyParameterKind,
    "name": str,
    "stiffness": Optional[float],
    "unit": str,
})

IdentifyPointOffset = TypedDict("IdentifyPointOffset", {
    "offset_mm": list[float],
    "point": int,
    "posture": str,
})

IdentifyPredictionSection = TypedDict("IdentifyPredictionSection", {
    "deflection_scores": Optional[list[float]],
    "folds": list[IdentifyFoldSection],
    "method": str,
    "model_error_pct": Optional[float],
    "noise_floor_mm": float,
    "postures": int,
    "score_q95": Optional[float],
    "score_q95_pct": Optional[float],
})

IdentifyRegionSection = TypedDict("IdentifyRegionSection", {
    "lower_deg": list[float],
    "margin_deg": float,
    "postures": int,
    "upper_deg": list[float],
})

IdentifyResidual = TypedDict("IdentifyResidual", {
    "line": NotRequired[int],
    "measured_mm": list[float],
    "norm_mm": float,
    "point": int,
    "posture": str,
    "predicted_mm": list[float],
    "residual_mm": list[float],
})

IdentifyRobust = TypedDict("IdentifyRobust", {
    "converged": bool,
    "down_weighted": list[IdentifyRow],
    "iterations": int,
    "loss": str,
    "scale_mm": float,
    "stop_reason": IdentifyStop,
    "tuning_constant": float,
})

IdentifyRow = TypedDict("IdentifyRow", {
    "coordinate": str,
    "line": NotRequired[int],
    "point": int,
    "posture": str,
    "residual_mm": float,
    "weight": float,
})

IdentifySpread = TypedDict("IdentifySpread", {
    "max": Optional[float],
    "mean": Optional[float],
    "min": Optional[float],
    "name": str,
    "std": Optional[float],
    "unit": str,
})

IdentifySpreadDoc = TypedDict("IdentifySpreadDoc", {
    "chosen_share": float,
    "kind": IdentifyParameterKind,
    "median": Optional[float],
    "name": str,
    "percentile_2_5": Optional[float],
    "percentile_97_5": Optional[float],
    "unit": str,
})

IdentifyStepDoc = TypedDict("IdentifyStepDoc", {
    "candidates": list[IdentifyModelDoc],
    "chosen": Optional[str],
})

IdentifyStop = Literal["converged", "stalled", "damping-exhausted", "iteration-limit"]

IdentifyVerdict = Literal["consistent", "model-error", "below-noise"]

IdentifyWarning = TypedDict("IdentifyWarning", {
    "kind": IdentifyWarningKind,
    "message": str,
})

IdentifyWarningKind = Literal["all-negative", "negative", "rigid", "units", "plausibility", "load-steps", "no-force", "unidentifiable", "meshes", "misfit", "feed", "near-postures", "old-field", "not-converged", "masses", "chatter", "configuration", "left-out", "extrapolation", "speed", "calibrated", "model-form", "encoding"]

IdentifyComparisonDocument = TypedDict("IdentifyComparisonDocument", {
    "bootstrap": NotRequired[Optional[IdentifyBootstrapDoc]],
    "conclusion": str,
    "data": str,
    "dropped": list[IdentifyDroppedDoc],
    "kind": Literal["identify-comparison"],
    "load_levels": int,
    "model_fits": bool,
    "models": list[IdentifyModelDoc],
    "nested": Optional[IdentifyNestedDoc],
    "nonlinear_separation": Optional[str],
    "recommended_fit": IdentifyFitDoc,
    "setup": str,
    "steps": list[IdentifyStepDoc],
})

IdentifyDrivesDocument = TypedDict("IdentifyDrivesDocument", {
    "active_bounds": Optional[list[bool]],
    "chi2_p_value": Optional[float],
    "chi2_statistic": Optional[float],
    "ci95_from_compliance_nm_per_rad": Optional[list[list[Optional[float]]]],
    "ci95_nm_per_rad": Optional[list[list[Optional[float]]]],
    "compliance_ci95_rad_per_nm": Optional[list[list[float]]],
    "compliance_covariance_rad2_per_nm2": Optional[list[list[float]]],
    "compliance_covariance_si": Optional[list[list[float]]],
    "compliance_rad_per_nm": list[float],
    "compliance_std_error_rad_per_nm": Optional[list[float]],
    "cond_psi": float,
    "cross_validation": Optional[IdentifyCrossValidation],
    "data": str,
    "degrees_of_freedom": Optional[int],
    "intervals_from": str,
    "kind": Literal["identify-drives"],
    "largest_residuals": list[IdentifyResidual],
    "load_steps": Optional[list[IdentifyLoadStep]],
    "method": str,
    "model_error_dominates": Optional[bool],
    "noise_ratio": Optional[float],
    "noise_std_mm": float,
    "nonnegative_stop_reason": NotRequired[Optional[IdentifyStop]],
    "offsets": Optional[list[IdentifyPointOffset]],
    "parameters": list[IdentifyParameterStiffness],
    "physical": list[bool],
    "poorly_determined": Optional[list[bool]],
    "poorly_determined_above_pct": float,
    "postures": int,
    "prediction": Optional[IdentifyPredictionSection],
    "region": Optional[IdentifyRegionSection],
    "residual_rms_mm": float,
    "residual_std_mm": Optional[float],
    "residuals": list[IdentifyResidual],
    "robust": Optional[IdentifyRobust],
    "rows": int,
    "setup": str,
    "springs": IdentifyCoordinates,
    "std_error_nm_per_rad": Optional[list[Optional[float]]],
    "std_error_pct": Optional[list[Optional[float]]],
    "stiffness_nm_per_rad": list[Optional[float]],
    "t_quantile": Optional[float],
    "tracker_noise": Optional[IdentifyIntervals],
    "unit_warning": Optional[str],
})

IdentifySpringsDocument = TypedDict("IdentifySpringsDocument", {
    "chi2_p_value": Optional[float],
    "compliance_covariance_si": Optional[list[list[float]]],
    "cross_validation": Optional[IdentifyCrossValidationDoc],
    "data": str,
    "degrees_of_freedom": int,
    "kind": Literal["identify-springs"],
    "method": str,
    "model_check": Optional[IdentifyVerdict],
    "model_form": NotRequired[Optional[IdentifyModelFormSection]],
    "noise_ratio": Optional[float],
    "noise_std_mm": float,
    "nonnegative_stop_reason": NotRequired[Optional[IdentifyStop]],
    "parameters": list[IdentifyParameterDoc],
    "postures": int,
    "prediction": Optional[IdentifyPredictionSection],
    "rank": int,
    "region": Optional[IdentifyRegionSection],
    "residual_rms_mm": float,
    "residuals": list[IdentifyResidual],
    "robust": Optional[IdentifyRobust],
    "rows": int,
    "scaled_cond": Optional[float],
    "setup": str,
    "unidentifiable": list[str],
    "warnings": list[IdentifyWarning],
})

# kinematics: docs/schemas/kinematics.schema.json

KinematicsDocument = TypedDict("KinematicsDocument", {
    "characteristic_length_mm": float,
    "characteristic_length_source": str,
    "coordinates": KinematicsCoordinates,
    "dexterity": Optional[float],
    "external": list[KinematicsExternalValue],
    "external_jacobian": Optional[list[list[float]]],
    "flange_position_mm": list[float],
    "flange_rotation": list[list[float]],
    "jacobian": list[list[float]],
    "joint_positions_mm": list[list[float]],
    "kind": Literal["kinematics"],
    "mass_matrix_kg_m2": Optional[list[list[float]]],
    "mode_shapes": Optional[list[KinematicsModeShape]],
    "natural_frequencies_hz": Optional[list[float]],
    "operational_inertia_si": Optional[list[list[float]]],
    "part_position_mm": Optional[list[float]],
    "part_rotation": Optional[list[list[float]]],
    "point_in_part_mm": Optional[list[float]],
    "point_mm": list[float],
    "point_position_mm": list[float],
    "q_deg": list[float],
    "robot": str,
    "robot_source": str,
    "warnings": list[KinematicsWarning],
})

KinematicsCoordinates = Literal["axis", "kinematic"]

KinematicsExternalValue = TypedDict("KinematicsExternalValue", {
    "column": str,
    "name": str,
    "role": str,
    "value": float,
})

KinematicsModeShape = TypedDict("KinematicsModeShape", {
    "frequency_hz": float,
    "joints": list[float],
    "point_direction": list[float],
})

KinematicsWarning = TypedDict("KinematicsWarning", {
    "kind": KinematicsWarningKind,
    "message": str,
})

KinematicsWarningKind = Literal["all-negative", "negative", "rigid", "units", "plausibility", "load-steps", "no-force", "unidentifiable", "meshes", "misfit", "feed", "near-postures", "old-field", "not-converged", "masses", "chatter", "configuration", "left-out", "extrapolation", "speed", "calibrated", "model-form", "encoding"]

# place: docs/schemas/place.schema.json

PlaceDocument = TypedDict("PlaceDocument", {
    "evaluations": int,
    "gain_vs_own_pct": Optional[float],
    "gain_vs_reach_only_pct": float,
    "kind": Literal["place"],
    "objective": str,
    "own": PlacePlacement,
    "placed": PlacePlacement,
    "reach_only": PlacePlacement,
    "warnings": list[PlaceWarning],
})

PlacePlacement = TypedDict("PlacePlacement", {
    "feasible": bool,
    "max_condition": Optional[float],
    "mean_bound_mm": Optional[float],
    "min_clearance_mm": Optional[float],
    "min_limit_margin_deg": Optional[float],
    "peak_bound_mm": Optional[float],
    "reason": Optional[str],
    "rpy_deg": list[float],
    "worst_line": Optional[int],
    "xyz_mm": list[float],
})

PlaceWarning = TypedDict("PlaceWarning", {
    "kind": PlaceWarningKind,
    "message": str,
})

PlaceWarningKind = Literal["all-negative", "negative", "rigid", "units", "plausibility", "load-steps", "no-force", "unidentifiable", "meshes", "misfit", "feed", "near-postures", "old-field", "not-converged", "masses", "chatter", "configuration", "left-out", "extrapolation", "speed", "calibrated", "model-form", "encoding"]

# plan: docs/schemas/plan.schema.json

PlanDocument = TypedDict("PlanDocument", {
    "anchor_mm": list[float],
    "bodies": Optional[PlanBodies],
    "criterion": Literal["classical", "zhang2021", "scaled-cond", "d-optimal", "relative-a", "test-pose"],
    "displacement_variance_multiple": float,
    "kind": Literal["plan"],
    "load_n": float,
    "load_steps_n": list[float],
    "measuring_points": int,
    "near_postures": list[PlanNearDoc],
    "noise_levels": list[float],
    "parameters": list[PlanParameter],
    "postures": list[PlanPlannedPosture],
    "predicted_deviation_pct": list[list[Optional[float]]],
    "robot": str,
    "setup": str,
    "target_pct": Optional[float],
    "unidentifiable": list[str],
    "virtual_springs": bool,
})

PlanBodies = TypedDict("PlanBodies", {
    "collision_shapes": Optional[int],
    "link_radii_mm": Optional[list[float]],
    "tool_radius_mm": float,
})

PlanNearDoc = TypedDict("PlanNearDoc", {
    "flange_angle_deg": float,
    "flange_distance_mm": float,
    "joint_distance_deg": float,
    "postures": list[int],
    "same_pose_other_branch": bool,
})

PlanParameter = TypedDict("PlanParameter", {
    "identified": bool,
    "name": str,
    "predicted_deviation_pct": Optional[float],
    "unit": str,
})

PlanPlannedPosture = TypedDict("PlanPlannedPosture", {
    "displacements_mm": list[list[float]],
    "failed_checks": list[str],
    "loading_point_z_mm": float,
    "min_clearance_mm": Optional[float],
    "min_margin_check": Optional[str],
    "min_margin_mm": Optional[float],
    "posture": int,
    "q_deg": list[float],
    "rope_direction": list[float],
    "rope_length_mm": float,
    "without_pct": list[Optional[float]],
    "without_worst_pct": Optional[float],
})

# predict: docs/schemas/predict.schema.json

PredictDocument = TypedDict("PredictDocument", {
    "cartesian_compliance": PredictComplianceDocument,
    "cartesian_stiffness": Optional[PredictStiffnessDocument],
    "compliance_along_force_mm_per_n": Optional[float],
    "effective_mass_free_kg": Optional[float],
    "effective_mass_kg": Optional[float],
    "effective_mass_std_kg": Optional[float],
    "extrapolates": Optional[bool],
    "flange_rotation_mrad": list[float],
    "flange_rotation_std_mrad": Optional[list[float]],
    "joint_deflections_mrad": list[float],
    "kind": Literal["predict"],
    "mass_matrix_kg_m2": Optional[list[list[float]]],
    "measuring_points": list[PredictPointDocument],
    "mode_shapes": Optional[list[PredictModeShape]],
    "natural_frequencies_hz": Optional[list[float]],
    "operational_inertia_si": Optional[list[list[float]]],
    "outside_region": list[PredictAxisOutside],
    "prediction_level": float,
    "q_deg": list[float],
    "region": Optional[PredictRegionSection],
    "setup": str,
    "stiffness_nm_per_rad": list[float],
    "surge_energy_j": Optional[float],
    "surge_mm_s": Optional[float],
    "surge_std_mm_s": Optional[float],
    "tcp_deflection_interval_mm": Optional[list[list[Optional[float]]]],
    "tcp_deflection_mm": list[float],
    "tcp_deflection_norm_mm": float,
    "tcp_deflection_std_mm": Optional[list[float]],
    "tcp_mm": list[float],
    "tcp_rotation_mrad": list[float],
    "tcp_rotation_std_mrad": Optional[list[float]],
    "torques_nm": list[float],
    "warnings": list[PredictWarning],
    "wrench_base_frame_n_nm": list[float],
    "wrench_frame": str,
    "wrench_n_nm": list[float],
    "wrench_point_mm": list[float],
})

PredictAxisOutside = TypedDict("PredictAxisOutside", {
    "axis": int,
    "identified_deg": list[float],
    "q_deg": float,
})

PredictComplianceDocument = TypedDict("PredictComplianceDocument", {
    "matrix_mm_mrad_per_kn_knm": list[list[float]],
    "matrix_si": list[list[float]],
    "rotation_per_force_rad_per_n": list[list[float]],
    "rotation_per_moment_rad_per_nm": list[list[float]],
    "translation_per_force_m_per_n": list[list[float]],
    "translation_per_moment_m_per_nm": list[list[float]],
})

PredictModeShape = TypedDict("PredictModeShape", {
    "frequency_hz": float,
    "joints": list[float],
    "point_direction": list[float],
})

PredictPointDocument = TypedDict("PredictPointDocument", {
    "displacement_interval_mm": Optional[list[list[Optional[float]]]],
    "displacement_mm": list[float],
    "displacement_norm_mm": float,
    "displacement_std_mm": Optional[list[float]],
    "point": int,
    "position_mm": list[float],
})

PredictRegionSection = TypedDict("PredictRegionSection", {
    "lower_deg": list[float],
    "margin_deg": float,
    "postures": int,
    "upper_deg": list[float],
})

PredictStiffnessDocument = TypedDict("PredictStiffnessDocument", {
    "force_per_rotation_n_per_rad": list[list[float]],
    "force_per_translation_n_per_m": list[list[float]],
    "matrix_n_nm_per_um_urad": list[list[float]],
    "matrix_si": list[list[float]],
    "moment_per_rotation_nm_per_rad": list[list[float]],
    "moment_per_translation_nm_per_m": list[list[float]],
})

PredictWarning = TypedDict("PredictWarning", {
    "kind": PredictWarningKind,
    "message": str,
})

PredictWarningKind = Literal["all-negative", "negative", "rigid", "units", "plausibility", "load-steps", "no-force", "unidentifiable", "meshes", "misfit", "feed", "near-postures", "old-field", "not-converged", "masses", "chatter", "configuration", "left-out", "extrapolation", "speed", "calibrated", "model-form", "encoding"]

# register-postures: docs/schemas/register-postures.schema.json

RegisterPosturesDocument = TypedDict("RegisterPosturesDocument", {
    "candidates": int,
    "checks": list[str],
    "evaluations": int,
    "feasible": int,
    "kind": Literal["register-postures"],
    "measuring_points": int,
    "method": str,
    "noise_std_mm": float,
    "postures": list[RegisterPosturesProposedPosture],
    "random_median_rotation_std_total_deg": float,
    "readings_template": str,
    "rotation_std_deg": list[float],
    "rotation_std_total_deg": float,
    "seed": int,
    "setup": str,
    "translation_std_mm": list[float],
})

RegisterPosturesProposedPosture = TypedDict("RegisterPosturesProposedPosture", {
    "posture": str,
    "q_deg": list[float],
})

# register: docs/schemas/register.schema.json

RegisterDocument = TypedDict("RegisterDocument", {
    "data": str,
    "fragment": str,
    "kind": Literal["register"],
    "noise_only_std": RegisterTransformStd,
    "noise_std_mm": float,
    "points": list[RegisterResidual],
    "residual_rms_mm": float,
    "robot_frame_sd_mm": float,
    "robot_frame_sd_mrad": float,
    "rotation_std_deg": list[float],
    "rpy_deg": list[float],
    "setup": str,
    "translation_std_mm": list[float],
    "xyz_mm": list[float],
})

RegisterResidual = TypedDict("RegisterResidual", {
    "line": int,
    "point": int,
    "posture": str,
    "residual_mm": list[float],
    "residual_norm_mm": float,
})

RegisterTransformStd = TypedDict("RegisterTransformStd", {
    "rotation_std_deg": list[float],
    "translation_std_mm": list[float],
})

# reproduce: docs/schemas/reproduce.schema.json

ReproduceDocument = TypedDict("ReproduceDocument", {
    "elapsed_s": float,
    "findings": ReproduceFindingsJson,
    "generator": str,
    "groups": list[ReproduceGroupSummary],
    "kind": Literal["reproduce"],
    "levels": list[float],
    "runs": int,
    "seed": int,
    "setup": ReproduceSetupJson,
    "start_trials": list[ReproduceTrialJson],
    "test_deflection_mm": list[list[list[float]]],
    "validation_level": int,
    "version": str,
})

ReproduceAxisMapJson = TypedDict("ReproduceAxisMapJson", {
    "matrix": list[list[float]],
    "offset_deg": list[float],
})

ReproduceBoundsJson = TypedDict("ReproduceBoundsJson", {
    "lower_deg": list[float],
    "upper_deg": list[float],
})

ReproduceCoordinates = Literal["axis", "kinematic"]

ReproduceExternalAxisJson = TypedDict("ReproduceExternalAxisJson", {
    "column": str,
    "direction": list[float],
    "error_motions": list[list[float]],
    "limits": list[float],
    "name": str,
    "offset": float,
    "point_mm": list[float],
    "role": str,
})

ReproduceFindingsJson = TypedDict("ReproduceFindingsJson", {
    "group3_beats_groups_1_and_2": bool,
    "group3_factor_vs_group1": Optional[float],
    "group3_factor_vs_group2": Optional[float],
    "prediction_mean_abs_relative_error": float,
    "relative_a_factor_vs_group3": Optional[float],
    "sentences": list[str],
    "start_groups": int,
    "start_groups_where_zhang2021_beats_both": int,
})

ReproduceFrameJson = TypedDict("ReproduceFrameJson", {
    "rotation_quaternion_wxyz": list[float],
    "translation_mm": list[float],
})

ReproduceGroupSummary = TypedDict("ReproduceGroupSummary", {
    "average_deviation_pct": float,
    "classical": Optional[float],
    "cond_psi": Optional[float],
    "criterion": Optional[str],
    "d_optimal": Optional[float],
    "mean_deviation_pct": list[list[float]],
    "mean_spring_stiffness": NotRequired[list[list[float]]],
    "mean_stiffness_nm_per_rad": list[list[float]],
    "name": str,
    "postures_deg": list[list[float]],
    "predicted_deviation_pct": list[list[float]],
    "relative_a": Optional[float],
    "scaled_cond": Optional[float],
    "search": str,
    "search_evaluations": int,
    "std_deviation_pct": list[list[float]],
    "test_pose_mm": Optional[float],
    "title": str,
    "validation_error_mm": list[list[float]],
    "zhang2021": Optional[float],
})

ReproduceJointJson = TypedDict("ReproduceJointJson", {
    "axis": list[float],
    "offset_deg": float,
    "post": ReproduceFrameJson,
    "pre": ReproduceFrameJson,
})

ReproduceLoadingJson = TypedDict("ReproduceLoadingJson", {
    "anchor_mm": list[float],
    "load_n": float,
})

ReproduceNoiseJson = TypedDict("ReproduceNoiseJson", {
    "displacement_variance_mm2": float,
    "level_multiples": list[float],
    "reading_sd_mm": float,
})

ReproduceRobotJson = TypedDict("ReproduceRobotJson", {
    "base": ReproduceFrameJson,
    "external_axes": list[ReproduceExternalAxisJson],
    "flange": ReproduceFrameJson,
    "joints": list[ReproduceJointJson],
    "lower_limit_deg": list[float],
    "name": str,
    "reference": str,
    "source": str,
    "upper_limit_deg": list[float],
})

ReproduceSetupJson = TypedDict("ReproduceSetupJson", {
    "axis_map": ReproduceAxisMapJson,
    "bounds": ReproduceBoundsJson,
    "characteristic_length_mm": Optional[float],
    "description": str,
    "loading": ReproduceLoadingJson,
    "name": str,
    "noise": ReproduceNoiseJson,
    "robot": ReproduceRobotJson,
    "springs": ReproduceCoordinates,
    "stiffness_nm_per_rad": Optional[list[float]],
    "test_postures_deg": list[list[float]],
    "tool": ReproduceToolJson,
})

ReproduceToolJson = TypedDict("ReproduceToolJson", {
    "loading_point_mm": list[float],
    "measuring_points_mm": list[list[float]],
    "tcp_mm": list[float],
})

ReproduceTrialJson = TypedDict("ReproduceTrialJson", {
    "classical_predicted_average_pct": float,
    "seed": int,
    "start_predicted_average_pct": float,
    "zhang2021_predicted_average_pct": float,
})

# select: docs/schemas/select.schema.json

SelectDocument = TypedDict("SelectDocument", {
    "calibration": NotRequired[Optional[SelectCalibrationDoc]],
    "calibration_weight": NotRequired[Optional[float]],
    "candidates": NotRequired[Optional[SelectForCandidates]],
    "criteria": SelectCriteria,
    "criterion": Literal["classical", "zhang2021", "scaled-cond", "d-optimal", "relative-a", "test-pose"],
    "elapsed_s": float,
    "evaluations": int,
    "for": str,
    "gradient": NotRequired[Optional[str]],
    "kind": Literal["select"],
    "margin_mm": float,
    "min_margin_mm": list[Optional[float]],
    "near_postures": list[SelectNearDoc],
    "out": NotRequired[Optional[str]],
    "pool": NotRequired[Optional[SelectPool]],
    "posture_stations": NotRequired[list[dict[str, float]]],
    "postures_deg": list[list[float]],
    "report": NotRequired[Optional[str]],
    "search": Literal["local", "global", "pool"],
    "seed": int,
    "setup": str,
    "solver": NotRequired[Literal["slsqp", "active-set"]],
    "start_value": Optional[float],
    "station": NotRequired[Optional[dict[str, float]]],
    "stations": NotRequired[list[SelectStationDoc]],
    "target": NotRequired[Optional[SelectTarget]],
    "termination": NotRequired[Literal["converged", "step-tolerance", "evaluation-limit", "line-search-failed", "infeasible", "subproblem-failed"]],
    "terminations": NotRequired[Optional[list[SelectTerminationCount]]],
    "unconstrained": NotRequired[Optional[SelectFree]],
    "value": Optional[float],
})

SelectCalibrationDoc = TypedDict("SelectCalibrationDoc", {
    "criterion": str,
    "d_optimality_mm2": float,
    "geometry": str,
    "gravity": str,
    "o1_mm": float,
    "o3_mm": float,
    "o4_mm": float,
    "o5_mm": float,
    "parameters": int,
    "predicted_rms_mm": Optional[float],
})

SelectCandidateDoc = TypedDict("SelectCandidateDoc", {
    "family": str,
    "identified": bool,
    "kind": str,
    "name": str,
    "needs_load_steps": bool,
    "separation": float,
    "unidentifiable": list[str],
})

SelectCriteria = TypedDict("SelectCriteria", {
    "classical": Optional[float],
    "cond_psi": Optional[float],
    "d_optimal": Optional[float],
    "infinite": list[SelectInfiniteCriterion],
    "predicted_deviation_pct": Optional[list[list[Optional[float]]]],
    "relative_a": Optional[float],
    "relative_std": Optional[list[Optional[float]]],
    "scaled_cond": Optional[float],
    "test_pose_mm": Optional[float],
    "zhang2021": Optional[float],
})

SelectDroppedDoc = TypedDict("SelectDroppedDoc", {
    "name": str,
    "reason": str,
})

SelectForCandidates = TypedDict("SelectForCandidates", {
    "candidates": list[SelectCandidateDoc],
    "designable": list[str],
    "designed": list[str],
    "dropped": list[SelectDroppedDoc],
    "load_levels": int,
    "nonlinear": list[str],
    "nonlinear_separation": Optional[str],
    "not_designable": list[SelectDroppedDoc],
    "separable": list[str],
    "together": bool,
    "together_unidentifiable": list[str],
})

SelectFree = TypedDict("SelectFree", {
    "cost_pct": Optional[float],
    "criteria": SelectCriteria,
    "feasible_predicted_average_pct": Optional[float],
    "postures_deg": list[list[float]],
    "predicted_average_change_pct": Optional[float],
    "predicted_average_pct": Optional[float],
    "termination": Literal["converged", "step-tolerance", "evaluation-limit", "line-search-failed", "infeasible", "subproblem-failed"],
    "value": Optional[float],
})

SelectInfinite = Literal["singular", "not-separable", "overflow"]

SelectInfiniteCriterion = TypedDict("SelectInfiniteCriterion", {
    "criterion": str,
    "reason": SelectInfinite,
})

SelectNearDoc = TypedDict("SelectNearDoc", {
    "flange_angle_deg": float,
    "flange_distance_mm": float,
    "joint_distance_deg": float,
    "postures": list[int],
    "same_pose_other_branch": bool,
})

SelectPool = TypedDict("SelectPool", {
    "chosen": list[int],
    "file": str,
    "method": str,
    "not_distinct": list[list[int]],
    "postures": int,
    "skipped": list[SelectSkipped],
    "usable": int,
})

SelectSkipped = TypedDict("SelectSkipped", {
    "checks": list[str],
    "posture": int,
    "reason": str,
})

SelectStationDoc = TypedDict("SelectStationDoc", {
    "value": Optional[float],
})

SelectStep = TypedDict("SelectStep", {
    "deviation_pct": list[Optional[float]],
    "postures": int,
    "worst_joint": int,
    "worst_joint_pct": Optional[float],
})

SelectTarget = TypedDict("SelectTarget", {
    "postures": int,
    "steps": list[SelectStep],
    "target_pct": float,
})

SelectTerminationCount = TypedDict("SelectTerminationCount", {
    "searches": int,
    "termination": Literal["converged", "step-tolerance", "evaluation-limit", "line-search-failed", "infeasible", "subproblem-failed"],
})

# simulate: docs/schemas/simulate.schema.json

SimulateDocument = TypedDict("SimulateDocument", {
    "groups": list[SimulateGroup],
    "kind": Literal["simulate"],
    "levels": list[float],
    "parameters": list[SimulateNamed],
    "runs": int,
    "seed": int,
    "setup": str,
})

SimulateGroup = TypedDict("SimulateGroup", {
    "mean_deviation_pct": list[list[float]],
    "mean_spring_stiffness": NotRequired[list[list[float]]],
    "mean_stiffness_nm_per_rad": list[list[float]],
    "name": str,
    "predicted_deviation_pct": list[list[float]],
    "std_deviation_pct": list[list[float]],
})

SimulateNamed = TypedDict("SimulateNamed", {
    "name": str,
    "unit": str,
})

# stiffness: docs/schemas/stiffness.schema.json

StiffnessDocument = TypedDict("StiffnessDocument", {
    "compliance_covariance_rad2_per_nm2": NotRequired[Optional[list[list[float]]]],
    "compliance_covariance_si": NotRequired[Optional[list[list[float]]]],
    "fitted": NotRequired[Optional[list[bool]]],
    "gravity": NotRequired[Optional[StiffnessGravitySection]],
    "kind": NotRequired[Optional[StiffnessFileKind]],
    "model_form": NotRequired[Optional[StiffnessModelFormSection]],
    "parameters": NotRequired[Optional[list[StiffnessParameterStiffness]]],
    "prediction": NotRequired[Optional[StiffnessPredictionSection]],
    "region": NotRequired[Optional[StiffnessRegionSection]],
    "stiffness_nm_per_rad": NotRequired[Optional[list[float]]],
    "unidentifiable": NotRequired[Optional[list[str]]],
})

StiffnessFileKind = Literal["stiffness", "identify-drives", "identify-springs"]

StiffnessFoldSection = TypedDict("StiffnessFoldSection", {
    "compliance_si": list[float],
    "postures": list[str],
    "scores": list[float],
})

StiffnessFormLaw = Literal["linear", "lost-motion", "load-dependent"]

StiffnessFormModelSection = TypedDict("StiffnessFormModelSection", {
    "compliance_si": list[list[float]],
    "springs": list[str],
})

StiffnessFormSpring = TypedDict("StiffnessFormSpring", {
    "axis": list[float],
    "kind": StiffnessKind,
    "law": StiffnessFormLaw,
    "link": int,
    "name": str,
    "point_mm": list[float],
})

StiffnessGravitySection = TypedDict("StiffnessGravitySection", {
    "model": str,
    "terms": list[StiffnessGravityTerm],
})

StiffnessGravityTerm = TypedDict("StiffnessGravityTerm", {
    "name": str,
    "value_si": float,
})

StiffnessKind = Literal["rotation", "translation"]

StiffnessModelFormSection = TypedDict("StiffnessModelFormSection", {
    "models": list[StiffnessFormModelSection],
    "recommended": NotRequired[Optional[StiffnessFormModelSection]],
    "resamples": int,
    "seed": int,
    "springs": list[StiffnessFormSpring],
})

StiffnessParameterKind = Literal["drive", "rotation", "translation", "lost-motion", "load-dependent"]

StiffnessParameterStiffness = TypedDict("StiffnessParameterStiffness", {
    "ci95": NotRequired[Optional[list[Optional[float]]]],
    "identified": NotRequired[Optional[bool]],
    "kind": StiffnessParameterKind,
    "name": str,
    "stiffness": NotRequired[Optional[float]],
    "unit": str,
})

StiffnessPredictionSection = TypedDict("StiffnessPredictionSection", {
    "deflection_scores": NotRequired[Optional[list[float]]],
    "folds": list[StiffnessFoldSection],
    "method": str,
    "model_error_pct": NotRequired[Optional[float]],
    "noise_floor_mm": float,
    "postures": int,
    "score_q95": NotRequired[Optional[float]],
    "score_q95_pct": NotRequired[Optional[float]],
})

StiffnessRegionSection = TypedDict("StiffnessRegionSection", {
    "lower_deg": list[float],
    "margin_deg": float,
    "postures": int,
    "upper_deg": list[float],
})

# validate: docs/schemas/validate.schema.json

ValidateDocument = TypedDict("ValidateDocument", {
    "checks": list[ValidateCheck],
    "data": str,
    "explained": float,
    "explained_pct": float,
    "extrapolated_postures": Optional[int],
    "kind": Literal["validate"],
    "max_delta_b_mm": float,
    "max_measured_mm": float,
    "mean_delta_b_mm": float,
    "mean_measured_mm": float,
    "parameters": list[ValidateParameterStiffness],
    "prediction_intervals": Optional[ValidatePredictionIntervals],
    "region": Optional[ValidateRegionSection],
    "rms_delta_b_mm": float,
    "rms_measured_mm": float,
    "setup": str,
})

ValidateCheck = TypedDict("ValidateCheck", {
    "delta_b_mm": float,
    "extrapolates": Optional[bool],
    "interval_mm": Optional[list[list[Optional[float]]]],
    "line": NotRequired[int],
    "measured_mm": list[float],
    "point": int,
    "posture": str,
    "predicted_mm": list[float],
})

ValidateParameterKind = Literal["drive", "rotation", "translation", "lost-motion", "load-dependent"]

ValidateParameterStiffness = TypedDict("ValidateParameterStiffness", {
    "ci95": NotRequired[Optional[list[Optional[float]]]],
    "identified": NotRequired[Optional[bool]],
    "kind": ValidateParameterKind,
    "name": str,
    "stiffness": Optional[float],
    "unit": str,
})

ValidatePredictionIntervals = TypedDict("ValidatePredictionIntervals", {
    "coordinates": int,
    "coverage": float,
    "coverage_pct": float,
    "covered": int,
    "level": float,
    "method": str,
})

ValidateRegionSection = TypedDict("ValidateRegionSection", {
    "lower_deg": list[float],
    "margin_deg": float,
    "postures": int,
    "upper_deg": list[float],
})
