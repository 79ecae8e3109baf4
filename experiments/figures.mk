# figures.mk: the rule of `make figures`: the PNGs in FIGURES/ drawn by
# experiments/analysis/figures.py from the grid's analysis files (TABLE.csv,
# RUNS_CSV, CELLS_CSV of `make reproduce-table`) and the renders RUNS_CSV
# names: fig3.png (Figure 3 at 1:1 with the signed difference),
# fig3-errors.png, fig2.png (from one render with --dump-reps, made here),
# tradeoff.png (with the rep-study's rules when REP_STUDY-cells.csv exists),
# ratio-vs-n.png and phases.png. Variables: experiments/config.mk.

# Figure 2's render: the precomputed method with the representatives dumped
$(FIG2_DIR)/reps.csv: | $(BUILD)/photonmap
	@mkdir -p $(FIG2_DIR)
	$(PM) render $(SCENE) --method precomputed --photons $(FIG2_PHOTONS) --nn $(FIG2_NN) --seed $(FIG_SEED) \
	  --width $(WIDTH) --height $(HEIGHT) --subpixels $(SUBPIXELS) --threads $(T_ARG) --quiet \
	  -o $(FIG2_DIR)/image.exr --stats $(FIG2_DIR)/stats.json --dump-reps $@

figures: $(FIG2_DIR)/reps.csv
	@$(PYTHON) -m experiments.analysis.figures --table $(TABLE).csv --runs $(RUNS_CSV) --cells-csv $(CELLS_CSV) \
	  --ref "$(FIG_REF)" --cells "$(FIG3_CELLS)" --paper-cells $(FIG3_PAPER_CELLS) --seed $(FIG_SEED) \
	  --crop $(FIG3_CROP) --crop-at $(FIG3_CROP_AT) --error-block $(FIG_ERROR_BLOCK) --time $(TIME) \
	  --fig2-dir $(FIG2_DIR) --fig2-plane $(FIG2_PLANE) --fig2-window "$(FIG2_WINDOW)" --scene $(SCENE) --pm $(PM) \
	  --rep-study-cells $(REP_STUDY)-cells.csv --out $(FIGURES)
