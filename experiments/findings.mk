# findings.mk: `make findings`: RESULTS/FINDINGS.md written by
# experiments/analysis/findings.py from the results files (every number read
# from them, every comparison worded from its test), and the check that
# every number of README.md's findings summary appears in some results file.
.PHONY: findings
findings:
	@$(PYTHON) -m experiments.analysis.findings --results $(RESULTS) --out $(RESULTS)/FINDINGS.md
	@$(PYTHON) -m experiments.analysis.findings --results $(RESULTS) --check-readme README.md
