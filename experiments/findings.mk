# findings.mk: `make findings`: one Python call (no renders, no DAG: the
# workflow engine would add nothing): RESULTS/FINDINGS.md written by
# experiments/analysis/findings.py from the results files (every number read
# from them, every comparison worded from its test); and, for the committed
# results/ only (findings.py's --readme), README.md's findings summary written from the same files
# (between its markers) and checked: the block is the one the files give,
# and every number of the section's other text appears in some results file.
.PHONY: findings
findings:
	@$(PYTHON) -m experiments.analysis.findings --results $(RESULTS) --out $(RESULTS)/FINDINGS.md --readme README.md
