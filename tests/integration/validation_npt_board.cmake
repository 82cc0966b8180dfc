anisodyn_add_script_test(validation_npt_board3.46_P0.0105 validation_npt_board.py SLOW ARGS manifests/validation/npt_board3.46_P0.0105.json)
anisodyn_add_script_test(validation_npt_board3.46_P0.0262 validation_npt_board.py SLOW ARGS manifests/validation/npt_board3.46_P0.0262.json)
