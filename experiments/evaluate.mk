# evaluate.mk: `make evaluate SCENE=my.scene [SIZE=WxH] [SEEDS=N] [OUT=dir]`:
# does the precomputed method pay on one scene? Five stages, one progress
# line each, every file under OUT (default results/evaluate/NAME):
#   1 pilot       OUT/pilot/pilot.json: one render; stops (exit 2) where the
#                 study is meaningless (photons escaping, the camera shut in
#                 a sphere, most samples at the eye-depth limit, many empty
#                 estimates), warns otherwise (experiments/analysis/evaluate.py)
#   2 POV-Ray     OUT/pov/{reference,fast}.exr: the committed references' rule
#                 (experiments/evaluate-pov.sh: 2W x 2H, 2x2 box), the
#                 rectangle thickness chosen from the geometry (OUT/pov/
#                 thickness.json) or the scene refused; cached in EVAL_CACHE
#                 by the exported SDL's hash
#   3 reference   our converged reference (experiments/analysis/reference.py:
#                 method-neutral, noise and bias measured; CONV_REF_* knobs),
#                 cross-checked against POV-Ray (OUT/crosscheck.json), at 2
#                 bounces where the full-bounce check fails
#   4 grid        PHOTONS x NNS x both methods x ESTIMATES x SEEDS, paired
#                 (experiments/study.mk), and the variants EVAL_VARIANTS
#   5 report      OUT/report.md and its images
# Knobs read: SCENE (required) SIZE SEEDS OUT PHOTONS NNS ESTIMATES THREADS
# TIME EE_TARGETS BOOTSTRAP BOOTSTRAP_SEED PM PYTHON CONV_REF_* EVAL_*; any
# other study knob given on the command line is refused (below).

# defaults: a few minutes on two cores
eval_size_default := 128x96
eval_seeds_default := 3
eval_photons_default := 25000 50000 100000
eval_nns_default := 10 30 100
# the variants run beside the grid (precomputed only; renderer/README.md)
EVAL_VARIANTS ?= lazy plane-lookup
# where the POV-Ray renders are kept between runs
EVAL_CACHE ?= $(BUILD)/evaluate-cache
# the scene exported to POV-Ray (default: SCENE itself; another file is the
# test's negative control: a wrong reference must be reported as such)
EVAL_POV_SCENE ?=
OUT ?=

ifneq ($(call goal,evaluate evaluate-references),)
$(if $(filter command line,$(origin SCENE)),,$(error evaluate: give SCENE=path/to/my.scene (the scene to evaluate)))
$(if $(wildcard $(SCENE)),,$(error evaluate: SCENE=$(SCENE): no such file))
# knobs evaluate does not read: refused, never silently ignored
eval_unread := REF REF_FAST TAG PM_ARGS CONV_RUNROOT METHODS SUBPIXELS SCENES RES_SIZES RES_TARGETS RES_REF SCENES_CELL REP_RULES
$(foreach v,$(eval_unread),$(if $(filter command line environment,$(origin $(v))),\
  $(error evaluate: $(v) is not read by evaluate (it runs both methods at 2x2 subpixels against its own references): leave it unset)))
eval_size := $(call knob,SIZE,$(eval_size_default))
eval_seeds := $(call knob,SEEDS,$(eval_seeds_default))
eval_photons := $(call knob,PHOTONS,$(eval_photons_default))
eval_nns := $(call knob,NNS,$(eval_nns_default))
eval_out := $(or $(strip $(OUT)),$(RESULTS)/evaluate/$(SCENE_NAME))
eval_key := $(shell sha256sum < $(SCENE) | cut -c1-12)
eval_pov_scene := $(or $(strip $(EVAL_POV_SCENE)),$(SCENE))
eval_w := $(call size_w,$(eval_size))
eval_h := $(call size_h,$(eval_size))
EVAL_GRID_SEEDS := $(call seeds,$(eval_seeds))
$(foreach v,$(EVAL_VARIANTS),$(if $(filter lazy plane-lookup plane,$(v)),,$(error evaluate: EVAL_VARIANTS: '$(v)' is none of lazy, plane-lookup, plane)))
# the pilot's setting: the grid's middle P_e and n
eval_mid = $(word $(shell echo $$(( ($(words $(1)) + 1) / 2 ))),$(shell echo $(1) | tr ' ' '\n' | sort -n))
eval_ref_p := $(or $(strip $(CONV_REF_PHOTONS)),$(shell echo $(eval_photons) | tr ' ' '\n' | sort -n | tail -n 1 | awk -v f=$(CONV_REF_FACTOR) '{ print $$1 * f }'))
eval_ref_dir := $(eval_out)/reference/$(eval_key)-p$(eval_ref_p)-n$(CONV_REF_NN)-$(CONV_REF_DIRECT)-seeds$(subst $(space),_,$(strip $(CONV_REF_SEEDS)))
eval_ref := $(eval_ref_dir)/$(eval_size).exr
eval_ref_b2 := $(eval_ref_dir)/b2-$(eval_size).exr
eval_runroot := $(eval_out)/runs/grid-$(eval_key)-$(eval_size)-$(T_LABEL)
eval_ref_build = $(PYTHON) -m experiments.analysis.reference build --pm $(PM) --scene $(SCENE) --width $(eval_w) \
  --height $(eval_h) --subpixels 2 --photons $(eval_ref_p) --nn $(CONV_REF_NN) --direct $(CONV_REF_DIRECT) \
  --seeds "$(CONV_REF_SEEDS)" --grid-seeds "$(EVAL_GRID_SEEDS)"

# ---- stage 4's study (experiments/study.mk)
evalgrid_SCENE = $(SCENE)
evalgrid_SIZE = $(eval_size)
evalgrid_SEEDS = $(eval_seeds)
evalgrid_PHOTONS = $(eval_photons)
evalgrid_NNS = $(eval_nns)
evalgrid_METHODS = conventional precomputed
evalgrid_ESTIMATES = $(ESTIMATES)
evalgrid_SUBPIXELS = 2
evalgrid_RUNROOT = $(eval_runroot)
evalgrid_REF = $(eval_ref)
evalgrid_REF_DEPS = $(eval_ref)
evalgrid_RUNS_CSV = $(eval_out)/grid/runs.csv
evalgrid_CELLS_CSV = $(eval_out)/grid/cells.csv
evalgrid_TABLE = $(eval_out)/grid/table
evalgrid_EQUAL_ERROR = $(eval_out)/grid/equal-error
$(eval $(call study,evalgrid))
eval_variant_args = $(if $(filter lazy,$(1)),--rep-eval lazy,--rep-gate $(1))
define eval_variant
evalvar-$(1)_SCENE = $$(SCENE)
evalvar-$(1)_SIZE = $$(eval_size)
evalvar-$(1)_SEEDS = $$(eval_seeds)
evalvar-$(1)_PHOTONS = $$(eval_photons)
evalvar-$(1)_NNS = $$(eval_nns)
evalvar-$(1)_METHODS = precomputed
evalvar-$(1)_ESTIMATES = $$(ESTIMATES)
evalvar-$(1)_SUBPIXELS = 2
evalvar-$(1)_PM_ARGS = $$(call eval_variant_args,$(1))
evalvar-$(1)_RUNROOT = $$(eval_runroot)-$(1)
evalvar-$(1)_CONV = $$(eval_runroot)
evalvar-$(1)_CONV_DEPS = $$(evalgrid_RUN_FILES)
evalvar-$(1)_REF = $$(eval_ref)
evalvar-$(1)_REF_DEPS = $$(eval_ref)
evalvar-$(1)_RUNS_CSV = $$(eval_out)/grid/runs-$(1).csv
evalvar-$(1)_CELLS_CSV = $$(eval_out)/grid/cells-$(1).csv
evalvar-$(1)_TABLE = $$(eval_out)/grid/table-$(1)
evalvar-$(1)_EQUAL_ERROR = $$(eval_out)/grid/equal-error-$(1)
$$(eval $$(call study,evalvar-$(1)))
endef
$(foreach v,$(EVAL_VARIANTS),$(eval $(call eval_variant,$(v))))
# the grid renders only after the references are checked
$(evalgrid_RUN_FILES) $(foreach v,$(EVAL_VARIANTS),$(evalvar-$(v)_RUN_FILES)): | $(eval_out)/crosscheck.json

.PHONY: evaluate evaluate-references evaluate-grid-line
# stages 1-3 only: the pilot and the references with their cross-check
evaluate-references: $(eval_out)/crosscheck.json
evaluate: $(eval_out)/report.md
	@echo "evaluate: done: $(eval_out)/report.md"

# ---- stage 1
$(eval_out)/pilot/pilot.json: $(SCENE) | $(BUILD)/photonmap $(DEPS_TEST)
	@echo "evaluate: [1/5] pilot: $(SCENE) at $(eval_size), P_e=$(call eval_mid,$(eval_photons)) n=$(call eval_mid,$(eval_nns))"
	@$(PYTHON) -m experiments.analysis.evaluate pilot --pm $(PM) --scene $(SCENE) --size $(eval_size) \
	  --photons $(call eval_mid,$(eval_photons)) --nn $(call eval_mid,$(eval_nns)) --out $(dir $@)

# ---- stage 2
$(eval_out)/pov/thickness.json: $(eval_pov_scene) $(eval_out)/pilot/pilot.json
	@echo "evaluate: [2/5] POV-Ray references of $(eval_pov_scene) at $(eval_size) (fast and reference presets)"
	@$(PYTHON) -m experiments.analysis.evaluate thickness --pm $(PM) --scene $(eval_pov_scene) --out $@ > /dev/null
eval_thick = $$($(PYTHON) -c 'import json, sys; print(json.load(open(sys.argv[1]))["rect_thickness"])' $(eval_out)/pov/thickness.json)
eval_pov = PM=$(PM) bash experiments/evaluate-pov.sh $(eval_pov_scene) $(eval_w) $(eval_h) $(EVAL_CACHE)
$(eval_out)/pov/reference.exr: $(eval_out)/pov/thickness.json
	@$(eval_pov) $@ --quality reference --rect-thickness $(eval_thick)
$(eval_out)/pov/fast.exr: $(eval_out)/pov/thickness.json
	@$(eval_pov) $@ --quality fast --rect-thickness $(eval_thick)

# ---- stage 3
$(eval_ref): $(SCENE) | $(eval_out)/pilot/pilot.json $(eval_out)/pov/reference.exr $(eval_out)/pov/fast.exr $(BUILD)/photonmap
	@echo "evaluate: [3/5] converged reference: corrected, --direct $(CONV_REF_DIRECT), P_e=$(eval_ref_p) n=$(CONV_REF_NN), seeds $(CONV_REF_SEEDS), and each at P_e/2"
	@$(eval_ref_build) --dir $(eval_ref_dir)/$(eval_size) --out $@ | grep -v '^reference: .* seed '
$(eval_out)/crosscheck.json: $(eval_ref) $(eval_out)/pov/reference.exr $(eval_out)/pov/fast.exr
	@$(PYTHON) -m experiments.analysis.evaluate crosscheck --ref $(eval_ref) --pov-ref $(eval_out)/pov/reference.exr \
	  --pov-fast $(eval_out)/pov/fast.exr --out $@.full > /dev/null
	@if $(PYTHON) -c 'import json, sys; sys.exit(json.load(open(sys.argv[1]))["agree"] != "full")' $@.full; then \
	  mv $@.full $@; \
	else \
	  echo "evaluate: [3/5] full bounces disagree: the bounce-limited comparison (export-pov --bounces 2 against --photon-depth 3)"; \
	  $(eval_pov) $(eval_out)/pov/b2-reference.exr --quality reference --bounces 2 --rect-thickness $(eval_thick) && \
	  $(eval_ref_build) --pm-args "--photon-depth 3" --dir $(eval_ref_dir)/b2-$(eval_size) --out $(eval_ref_b2) | grep -v '^reference: .* seed ' && \
	  rm -f $@.full && \
	  $(PYTHON) -m experiments.analysis.evaluate crosscheck --ref $(eval_ref) --pov-ref $(eval_out)/pov/reference.exr \
	    --pov-fast $(eval_out)/pov/fast.exr --b2-ours $(eval_ref_b2) --b2-pov $(eval_out)/pov/b2-reference.exr --out $@ > /dev/null; \
	fi
	@$(PYTHON) -c 'import json, sys; d = json.load(open(sys.argv[1])); print("evaluate: [3/5] references:", d["sentence"])' $@

# ---- stage 4 and 5
evaluate-grid-line: | $(eval_out)/crosscheck.json
	@echo "evaluate: [4/5] grid: $(words $(evalgrid_RUN_FILES) $(foreach v,$(EVAL_VARIANTS),$(evalvar-$(v)_RUN_FILES))) renders (P_e {$(eval_photons)} x n {$(eval_nns)} x both methods x {$(ESTIMATES)} x seeds 1..$(eval_seeds), variants {$(EVAL_VARIANTS)}), paired"
$(eval_out)/report.md: $(eval_out)/crosscheck.json evaluate-grid-line evalgrid-table $(EVAL_VARIANTS:%=evalvar-%-table)
	@$(PYTHON) -m experiments.analysis.evaluate report --scene $(SCENE) --pilot $(eval_out)/pilot/pilot.json \
	  --thickness $(eval_out)/pov/thickness.json --crosscheck $(eval_out)/crosscheck.json --ref $(eval_ref) \
	  --runs-csv $(evalgrid_RUNS_CSV) --table-csv $(evalgrid_TABLE).csv --equal-error-csv $(evalgrid_EQUAL_ERROR).csv \
	  --equal-error-png $(evalgrid_EQUAL_ERROR).png --runroot $(eval_runroot) --out $(eval_out) \
	  --estimates "$(ESTIMATES)" --time $(TIME) \
	  $(foreach v,$(EVAL_VARIANTS),--variant "$(v)=$(evalvar-$(v)_TABLE).csv,$(evalvar-$(v)_RUNS_CSV)") \
	  --settings "Scene \`$(SCENE)\` (content hash $(eval_key)) at $(eval_size), 2x2 subpixels, threads: $(or $(THREADS),all); grid P_e in {$(eval_photons)} x n in {$(eval_nns)} x both methods x estimates {$(ESTIMATES)} x seeds 1..$(eval_seeds), variants {$(EVAL_VARIANTS)}; time $(TIME); POV-Ray scene \`$(eval_pov_scene)\`; command: make evaluate SCENE=$(SCENE) SIZE=$(eval_size) SEEDS=$(eval_seeds) OUT=$(eval_out)"
endif
