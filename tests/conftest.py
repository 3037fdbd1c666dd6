"""Shared fixtures, and the tests the README's command leaves to ``-m slow``."""

import pytest

import ropemodel as rm


@pytest.fixture(scope="session")
def fig9():
    """The built-in example: Krauze et al. (2025), Fig. 9."""
    return rm.load_scene()


#: Tests measured at more than 2 s each on a 2-core machine (``pytest --durations=0``): they run with
#: ``-m slow`` (CI runs them after the README's command), so that the README's command stays under 5 minutes
#: on 2 cores.  A whole test is named by ``file::function``, one case of a parametrised test by its full id.
#: ``tests/test_house.py`` checks that every entry still names a test.  A test is slow by its own
#: ``@pytest.mark.slow`` where it is slow by design (10^4-point properties, the fuzz's generated families).
SLOW_BY_DURATION = (
    "tests/test_api_scenes.py::test_a_scene_a_name_and_a_path_give_the_same_answer[report]",
    "tests/test_budget.py::test_size_builds_few_cases_and_the_whole_nlp_is_counted",
    "tests/test_calcsheet.py::test_every_equation_of_every_variant_can_be_shown",
    "tests/test_calcsheet.py::test_the_sheet_holds_every_equation_the_page_shows",
    "tests/test_capstan_accuracy_properties.py::test_every_regime_against_an_independent_integration[smooth]",
    "tests/test_capstan_accuracy_properties.py::test_regime_one_10k_against_quadrature",
    "tests/test_cli_details.py::test_a_closed_pipe_ends_every_command_quietly",
    "tests/test_cli_details.py::test_head_c1_takes_one_byte_and_the_command_exits_0[long-curve]",
    "tests/test_docs.py::test_every_generated_block_matches_the_registry",
    "tests/test_docs.py::test_site_tables_match_the_registry",
    "tests/test_domains.py::test_every_model_is_walked",
    "tests/test_dynamic_sizing.py::test_cli_no_design_exits_1",
    "tests/test_dynamic_sizing.py::test_sweep_refuses_structural_parameters",
    "tests/test_envelope.py::test_the_report_lists_each_check_with_where_it_governs",
    "tests/test_interrupt.py::test_ctrl_c_during_dynamic_sizing_on_a_route",
    "tests/test_lining_accuracy_properties.py::test_a_tolerance_that_cannot_be_met_is_an_error",
    "tests/test_lining_accuracy_properties.py::test_every_integrator_meets_its_rtol[collocation]",
    "tests/test_overrides.py::test_every_value_changes_the_answer_or_is_named_unused[capstan_li_experiment-identify]",
    "tests/test_overrides.py::test_every_value_changes_the_answer_or_is_named_unused[koepe_braking-sensitivity]",
    "tests/test_overrides.py::test_every_value_changes_the_answer_or_is_named_unused[sheave_thirion-run]",
    "tests/test_overrides.py::test_every_value_changes_the_answer_or_is_named_unused[sheave_thirion-sensitivity]",
    "tests/test_overrides.py::test_every_value_changes_the_answer_or_is_named_unused[winch_sizing_voigt-size]",
    "tests/test_overrides.py::test_every_value_changes_the_answer_or_is_named_unused[winch_start_stroke-simulate]",
    "tests/test_overrides.py::test_every_value_changes_the_answer_or_is_named_unused[route3-solve]",
    "tests/test_overrides.py::test_every_value_changes_the_answer_or_is_named_unused[route3-sensitivity]",
    "tests/test_overrides.py::test_every_value_changes_the_answer_or_is_named_unused[route3-trip]",
    "tests/test_overrides.py::test_every_value_changes_the_answer_or_is_named_unused[route3-size]",
    "tests/test_overrides.py::test_every_value_reaches_a_sweep[route_segments]",
    "tests/test_overrides.py::test_every_value_reaches_a_sweep[sheave_thirion]",
    "tests/test_overrides.py::test_every_value_reaches_a_sweep[route3]",
    "tests/test_progress.py::test_a_bar_over_the_work",
    "tests/test_progress.py::test_progress_on_a_terminal[argv1-computing the Sobol indices]",
    "tests/test_progress.py::test_progress_on_a_terminal[argv2-building the transient]",
    "tests/test_progress.py::test_progress_on_a_terminal[argv5-report of]",
    "tests/test_progress.py::test_quiet_and_pipes_show_nothing",
    "tests/test_report.py::test_the_documented_way_to_add_a_section_works",
    "tests/test_report.py::test_the_page_refers_to_nothing_outside_itself[koepe_braking]",
    "tests/test_report.py::test_the_page_refers_to_nothing_outside_itself[winch_start]",
    "tests/test_report.py::test_the_page_refers_to_nothing_outside_itself[winch_start_brake]",
    "tests/test_report.py::test_the_page_refers_to_nothing_outside_itself[winch_start_capstan]",
    "tests/test_report.py::test_the_page_refers_to_nothing_outside_itself[winch_start_motor]",
    "tests/test_report_applies.py::test_each_scene_shows_the_sections_it_calls_for_and_no_other[route3]",
    "tests/test_report_applies.py::test_the_issues_route_reports_exit_0_with_every_section_computed",
    "tests/test_report_cli.py::test_cli_an_infeasible_sizing_is_reported_with_its_conflict",
    "tests/test_report_render.py::test_cli_prints_the_page_to_pdf",
    "tests/test_report_render.py::test_every_built_in_scene_renders_in_chromium",
    "tests/test_report_render.py::test_the_pdf_has_page_numbers_a_running_header_and_the_sign_off",
    "tests/test_report_render.py::test_the_pictures_are_drawn",
    "tests/test_route_prune.py::test_sizing_on_the_pruned_places_equals_sizing_on_every_place",
    "tests/test_route_prune.py::test_the_worst_place_is_a_kept_joint",
    "tests/test_scene_contract.py::test_bare_number_refused_in_a_file_and_in_set[koepe-lining-voigt-Q_R]",
    "tests/test_scene_contract.py::test_bare_number_refused_in_a_file_and_in_set[koepe-lining-voigt-lambda_R]",
    "tests/test_scene_contract.py::test_bare_number_refused_in_a_file_and_in_set[koepe-lining-voigt-Q_T]",
    "tests/test_scene_contract.py::test_bare_number_refused_in_a_file_and_in_set[koepe-lining-voigt-lambda_T]",
    "tests/test_scene_contract.py::test_bare_number_refused_in_vary_and_points[koepe-lining-voigt-Q_R]",
    "tests/test_scene_contract.py::test_bare_number_refused_in_vary_and_points[koepe-lining-voigt-lambda_R]",
    "tests/test_scene_contract.py::test_bare_number_refused_in_vary_and_points[koepe-lining-voigt-Q_T]",
    "tests/test_scene_contract.py::test_bare_number_refused_in_vary_and_points[koepe-lining-voigt-lambda_T]",
    "tests/test_scene_contract.py::test_infeasible_design_says_what_would_make_one",
    "tests/test_sizing.py::test_drum_too_small_is_reported_naming_the_drum",
    "tests/test_sizing.py::test_next_size_up_and_bonmin_agree",
    "tests/test_sizing.py::test_size_cli_json_when_infeasible",
    "tests/test_studies_capstan.py::test_capstan_smooth_cost_fast",
    "tests/test_studies_capstan_accuracy.py::test_capstan_accuracy_fast",
    "tests/test_studies_dynamics.py::test_dynamic_factor_study_fast",
    "tests/test_studies_dynamics.py::test_dynamics_accuracy_study_fast",
    "tests/test_studies_dynamics.py::test_dynamics_events_study_fast",
    "tests/test_studies_koepe.py::test_files_written",
    "tests/test_studies_lining.py::test_lining_accuracy_fast",
    "tests/test_studies_sizing.py::test_discrete_design_fast",
    "tests/test_studies_sizing.py::test_sizing_map_speed_fast",
    "tests/test_studies_startup.py::test_startup_ratios_meet_their_goals",
    "tests/test_studies_sweep.py::test_sizing_map_fast",
    "tests/test_studies_sweep.py::test_sweep_performance_fast",
    "tests/test_sweep_files.py::test_progress_bar_on_a_terminal_only",
    "tests/test_sweep_files.py::test_two_sweep_processes_on_one_output",
    "tests/test_sweep_models.py::test_sweep_equals_single_solves[sheave_thirion.toml]",
    "tests/test_sweep_resume.py::test_killed_sweep_resumes_to_the_same_file",
    "tests/test_sweep_sizing.py::test_active_set_map_equals_cold_ipopt_across_active_set_changes",
    "tests/test_sweep_sizing.py::test_infeasible_points_are_kept_and_marked",
    "tests/test_sweep_sizing.py::test_sobol_of_the_sizing_optimum",
    "tests/test_trip.py::test_the_rigid_rope_transient_is_the_same_trip",
)


@pytest.hookimpl(tryfirst=True)     # before -m deselects
def pytest_collection_modifyitems(config, items):
    whole = {e for e in SLOW_BY_DURATION if "[" not in e}
    cases = {e for e in SLOW_BY_DURATION if "[" in e}
    for item in items:
        if item.nodeid in cases or item.nodeid.split("[")[0] in whole:
            item.add_marker(pytest.mark.slow)
