# findings.mk: `make findings`: RESULTS/FINDINGS.md written by
# experiments/analysis/findings.py from the results files (every number read
# from them, every comparison worded from its test); and, for the committed
# results/ only, README.md's findings summary written from the same files
# (between its markers) and checked: the block is the one the files give,
# and every number of the section's other text appears in some results file.
.PHONY: findings
findings:
	@$(PYTHON) -m experiments.analysis.findings --results $(RESULTS) --out $(RESULTS)/FINDINGS.md
ifeq ($(RESULTS),results)
	@$(PYTHON) -m experiments.analysis.findings --results $(RESULTS) --write-readme README.md
	@$(PYTHON) -m experiments.analysis.findings --results $(RESULTS) --check-readme README.md
endif
