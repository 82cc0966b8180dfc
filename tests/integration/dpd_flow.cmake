anisodyn_add_script_test(dpd_flow dpd_flow.py)
