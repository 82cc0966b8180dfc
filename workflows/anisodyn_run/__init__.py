"""anisodyn-run: expands a study manifest into a DAG of stage jobs and runs it (architecture §6)."""
