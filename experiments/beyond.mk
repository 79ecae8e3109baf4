# beyond.mk: `make beyond`, the representative variants beyond the paper's
# rule measured side by side at equal error (included from the Makefile after
# studies.mk, whose converged_ref, knob and scene_id it uses).
#
# Cases: every scene of SCENES at SIZE (default 512x384), and cornell at each
# size of BEYOND_SIZES too. Per case one base study with both methods
# (conventional and the paper's precomputed rule, pairs back to back by
# experiments/pair.sh) and one study per variant of BEYOND_VARIANTS (the
# precomputed method with the variant's options, compared with the base
# study's conventional renders of the same seeds: the same photon map, so
# paired by seed, but not back to back). Every study is referenced with the
# converged render of its scene and size (studies.mk's converged_ref).
# experiments/analysis/beyond.py then writes BEYOND_DIR/beyond.{md,csv} and
# FIGURES/beyond.png.
#
#   make beyond SIZE=256x192 SEEDS=5 PHOTONS="20000 50000 100000" NNS="10 50" BEYOND_SIZES="256x192 512x384"
#
# The default run: SCENES (five scenes) at 512x384 and cornell at 256x192,
# 512x384 and 1024x768 (BEYOND_SIZES; 7 cases), P_e {50k, 100k, 500k} x n
# {10, 20, 50, 100}, 5 seeds (fewer give percentile-bootstrap intervals that
# cover well under 95%), 9 members per group (conventional, paper, lazy,
# gated and lazygated at 3 taus): 3,780 renders plus 7 converged references
# (CONV_REF_*: 8 renders each at 10M and 5M photons, n = 200). Measured on
# the 2-core development machine with `make -j2 beyond` (two groups at a
# time; each group's members still back to back): about 65 minutes, 40 for
# the six cases at 512x384 and 256x192 and 25 for cornell at 1024x768,
# references and the per-study analyses included; without -j about twice
# that. The check run `make beyond SIZE=128x96 BEYOND_SIZES=128x96 SEEDS=2
# PHOTONS="50000 100000" NNS="10 50" BEYOND_TAUS=0.1` (200 renders, 5
# references, 20 studies) takes a few minutes.
#
# The variants: lazy (--rep-eval lazy), gatedT (--rep-gate BEYOND_GATE
# --rep-gate-tau T), lazygatedT (both), for each T of BEYOND_TAUS (every tau
# is reported, on every scene: none is chosen on the scenes shown).

# knobs of this study (the common ones, SIZE SEEDS PHOTONS NNS SCENES
# ESTIMATES, mean what they mean for every study; config.mk)
BEYOND_SIZES ?= 256x192 512x384 1024x768
BEYOND_TAUS ?= 0.05 0.1 0.2
BEYOND_GATE ?= plane-lookup
BEYOND_DIR = $(RESULTS)/beyond
beyond_size_default := 512x384
beyond_seeds_default := 5
# the paper's estimate only (lazy and the gates are studied on its rule)
beyond_estimates_default := paper

beyond_size = $(call knob,SIZE,$(beyond_size_default))
beyond_seeds = $(call knob,SEEDS,$(beyond_seeds_default))
beyond_estimates = $(call knob,ESTIMATES,$(beyond_estimates_default))
BEYOND_VARIANTS ?= lazy $(foreach t,$(BEYOND_TAUS),gated$(t) lazygated$(t))
# beyond_args VARIANT: its render options
beyond_args = $(strip $(if $(filter lazy lazygated%,$1),--rep-eval lazy) \
  $(if $(filter gated% lazygated%,$1),--rep-gate $(BEYOND_GATE) --rep-gate-tau $(patsubst lazygated%,%,$(patsubst gated%,%,$1))) \
  $(if $(filter lazy gated% lazygated%,$1),,$(error beyond: variant '$1' is not lazy, gatedT or lazygatedT)))
# the cases NAME@SIZE@SCENEPATH
beyond_cases = $(sort $(foreach s,$(SCENES),$(call scene_id,$(s))@$(beyond_size)@$(s) \
  $(if $(filter cornell,$(call scene_id,$(s))),$(foreach z,$(BEYOND_SIZES),cornell@$(z)@$(s)))))
beyond_id = $(word 1,$(subst @, ,$1))-$(word 2,$(subst @, ,$1))

# beyond_case NAME@SIZE@SCENE: the base study bey-ID and its variants bey-ID-V
define beyond_case
bey-$(2)_SCENE = $(word 3,$(subst @, ,$(1)))
bey-$(2)_SIZE = $(word 2,$(subst @, ,$(1)))
bey-$(2)_SEEDS = $$(beyond_seeds)
bey-$(2)_PHOTONS = $$(PHOTONS)
bey-$(2)_NNS = $$(NNS)
bey-$(2)_METHODS = conventional precomputed
bey-$(2)_ESTIMATES = $$(beyond_estimates)
bey-$(2)_TAG = beyond
bey-$(2)_REF = $$(call converged_ref,$$(bey-$(2)_SCENE),$$(bey-$(2)_SIZE))
bey-$(2)_REF_DEPS = $$(bey-$(2)_REF)
bey-$(2)_RUNS_CSV = $$(BEYOND_DIR)/studies/runs-$(2)-paper.csv
bey-$(2)_CELLS_CSV = $$(BEYOND_DIR)/studies/cells-$(2)-paper.csv
bey-$(2)_TABLE = $$(BEYOND_DIR)/studies/table-$(2)-paper
bey-$(2)_EQUAL_ERROR = $$(BEYOND_DIR)/studies/equal-error-$(2)-paper
$$(eval $$(call study,bey-$(2)))
$$(foreach v,$$(BEYOND_VARIANTS),$$(eval $$(call beyond_variant,$(2),$$(v))))
endef
define beyond_variant
bey-$(1)-$(2)_SCENE = $$(bey-$(1)_SCENE)
bey-$(1)-$(2)_SIZE = $$(bey-$(1)_SIZE)
bey-$(1)-$(2)_SEEDS = $$(beyond_seeds)
bey-$(1)-$(2)_PHOTONS = $$(PHOTONS)
bey-$(1)-$(2)_NNS = $$(NNS)
bey-$(1)-$(2)_METHODS = precomputed
bey-$(1)-$(2)_ESTIMATES = $$(beyond_estimates)
bey-$(1)-$(2)_PM_ARGS = $$(call beyond_args,$(2))
bey-$(1)-$(2)_TAG = beyond-$(2)
bey-$(1)-$(2)_CONV = $$(bey-$(1)_RUNROOT)
bey-$(1)-$(2)_CONV_DEPS = $$(bey-$(1)_RUN_FILES)
bey-$(1)-$(2)_REF = $$(bey-$(1)_REF)
bey-$(1)-$(2)_REF_DEPS = $$(bey-$(1)_REF_DEPS)
bey-$(1)-$(2)_RUNS_CSV = $$(BEYOND_DIR)/studies/runs-$(1)-$(2).csv
bey-$(1)-$(2)_CELLS_CSV = $$(BEYOND_DIR)/studies/cells-$(1)-$(2).csv
bey-$(1)-$(2)_TABLE = $$(BEYOND_DIR)/studies/table-$(1)-$(2)
bey-$(1)-$(2)_EQUAL_ERROR = $$(BEYOND_DIR)/studies/equal-error-$(1)-$(2)
$$(eval $$(call study,bey-$(1)-$(2)))
endef
$(foreach c,$(beyond_cases),$(eval $(call beyond_case,$(c),$(call beyond_id,$(c)))))

# beyond_group ID,STEM: the renders of one (cell, seed) of case ID, the
# conventional, the paper's rule and every variant, one recipe back to back
# (experiments/group.sh: the order alternating with the seed). An explicit
# grouped rule: it takes the place of study.mk's pair and single-render
# pattern rules for these records, make -j runs it once, and a missing
# record of any member renders the whole group again.
beyond_stems = $(patsubst conventional-%,%,$(filter conventional-%,$(bey-$(1)_RUN_NAMES)))
define beyond_group
$(bey-$(1)_RUNROOT)/conventional-$(2).run.json $(bey-$(1)_RUNROOT)/precomputed-$(2).run.json \
  $(foreach v,$(BEYOND_VARIANTS),$(bey-$(1)-$(v)_RUNROOT)/precomputed-$(2).run.json) &: | $$(BUILD)/photonmap $$(DEPS_TEST)
	@$$(bey-$(1)_RUN_ENV) bash experiments/group.sh $(2) $(bey-$(1)_RUNROOT) conventional "" \
	  $(bey-$(1)_RUNROOT) precomputed "" \
	  $(foreach v,$(BEYOND_VARIANTS),$(bey-$(1)-$(v)_RUNROOT) precomputed "$(call beyond_args,$(v))")
endef
$(foreach i,$(foreach c,$(beyond_cases),$(call beyond_id,$(c))),$(foreach s,$(call beyond_stems,$(i)),$(eval $(call beyond_group,$(i),$(s)))))

beyond_ids = $(foreach c,$(beyond_cases),$(call beyond_id,$(c)))
.PHONY: beyond beyond-runs
beyond-runs: $(foreach i,$(beyond_ids),$(bey-$(i)_REF_DEPS) $(bey-$(i)_RUN_FILES) \
  $(foreach v,$(BEYOND_VARIANTS),$(bey-$(i)-$(v)_RUN_FILES)))
beyond: $(foreach i,$(beyond_ids),bey-$(i)-table $(BEYOND_VARIANTS:%=bey-$(i)-%-table)) | $(DEPS_TEST)
	@$(PYTHON) -m experiments.analysis.beyond \
	  $(foreach c,$(beyond_cases),--case $(call beyond_id,$(c)) $(word 1,$(subst @, ,$(c))) $(word 2,$(subst @, ,$(c))) \
	    $(bey-$(call beyond_id,$(c))_REF) \
	    --variant $(call beyond_id,$(c)) paper "" $(bey-$(call beyond_id,$(c))_RUNS_CSV) \
	    $(foreach v,$(BEYOND_VARIANTS),--variant $(call beyond_id,$(c)) $(v) "$(call beyond_args,$(v))" \
	      $(bey-$(call beyond_id,$(c))-$(v)_RUNS_CSV))) \
	  --time $(TIME) --bootstrap $(BOOTSTRAP) --bootstrap-seed $(BOOTSTRAP_SEED) --pm $(PM) --gate $(BEYOND_GATE) \
	  --settings "make$(if $(filter -j%,$(MAKEFLAGS)), $(filter -j%,$(MAKEFLAGS))) beyond SIZE=$(beyond_size) SEEDS=$(beyond_seeds) PHOTONS=\"$(PHOTONS)\" NNS=\"$(NNS)\" ESTIMATES=\"$(beyond_estimates)\" BEYOND_SIZES=\"$(BEYOND_SIZES)\" BEYOND_TAUS=\"$(BEYOND_TAUS)\" BEYOND_GATE=$(BEYOND_GATE) CONV_REF_PHOTONS=$(CONV_REF_PHOTONS) CONV_REF_FACTOR=$(CONV_REF_FACTOR) CONV_REF_NN=$(CONV_REF_NN) CONV_REF_SEEDS=\"$(CONV_REF_SEEDS)\" THREADS=$(THREADS) TIME=$(TIME) BOOTSTRAP=$(BOOTSTRAP)" \
	  --out $(BEYOND_DIR)/beyond --figure $(FIGURES)/beyond.png

ifneq ($(call goal,beyond beyond-runs),)
ifneq ($(filter command line,$(origin SCENE) $(origin REF) $(origin REF_FAST) $(origin TAG) $(origin PM_ARGS)),)
$(error beyond: runs every scene of SCENES (and cornell at BEYOND_SIZES) against its own converged reference, with its own variants: give SCENES="a.scene b.scene", not SCENE=, REF=, TAG= or PM_ARGS=)
endif
endif
