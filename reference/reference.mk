# reference.mk: `make reference` renders the POV-Ray references in
# reference/SCENE/ (see reference/README.md; SCENE is the first word of
# NAME, e.g. reference/cornell/cornell-fast-128x96.*). Each NAME gets NAME.pov (the exported
# scene), NAME.exr (linear half-float RGB) and NAME.log (versions, commands,
# POV-Ray's own statistics). POV-Ray runs single-threaded (+WT1, bit-
# reproducible) at 2W x 2H without antialiasing; oiiotool's box filter then
# averages each 2x2 block, which is exactly the renderer's 2x2 subpixel grid.
# The renders are committed; tests never need to re-render them.
#
#   make reference        every reference (the 1024x768 one takes a while)
#   make reference-small  all but the 1024x768 one

REF_DIR := reference
REF_TMP := $(BUILD)/reference
REF_SCENE := scenes/cornell.scene
REF_POVRAY_FLAGS := +FE -A -J +WT1 -D -V +GS
# ref_render NAME, SCENE, W, H, F, EXPORT-FLAGS: the rules for one reference,
# rendered at F*W x F*H and box-filtered by F (F = 2: the renderer's default
# 2x2 subpixels; F = 1: one centre sample per pixel)
# ref_path NAME: reference/SCENE/NAME (no extension)
ref_path = $(REF_DIR)/$(firstword $(subst -, ,$(1)))/$(1)
define ref_render
$(call ref_path,$(1)).pov: $(2) renderer/povray.c $(BUILD)/photonmap
	@mkdir -p $(REF_TMP)
	$(BUILD)/photonmap export-pov $(2) --width $$$$(($(3) * $(5))) --height $$$$(($(4) * $(5))) $(6) -o $(REF_TMP)/$(1).pov
	@if cmp -s $(REF_TMP)/$(1).pov $$@; then echo "$$@ unchanged"; else mv $(REF_TMP)/$(1).pov $$@; fi

$(call ref_path,$(1)).exr: $(call ref_path,$(1)).pov
	@mkdir -p $(REF_TMP)
	{ echo "reference $(1): $(3)x$(4), rendered at $$$$(($(3) * $(5)))x$$$$(($(4) * $(5))) and box-downsampled by $(5)"; \
	  echo "export: build/photonmap export-pov $(2) --width $$$$(($(3) * $(5))) --height $$$$(($(4) * $(5))) $(6)"; \
	  echo "povray: nice povray +I$$< +O$(REF_TMP)/$(1)-raw.exr +W$$$$(($(3) * $(5))) +H$$$$(($(4) * $(5))) $(REF_POVRAY_FLAGS)"; \
	  echo "downsample: oiiotool $(REF_TMP)/$(1)-raw.exr --resize:filter=box $(3)x$(4) -d half -o $$@"; \
	  echo "version: $$$$(povray --version 2>&1 | grep -m1 POV-Ray); $$$$(dpkg-query -W povray 2>/dev/null); $$$$(oiiotool --version 2>&1 | head -n1)"; \
	  echo "host: $$$$(uname -m), $$$$(nproc) cores; date: $$$$(date -u +%Y-%m-%dT%H:%MZ)"; \
	  echo "---- povray output"; } > $(REF_TMP)/$(1).log
	/usr/bin/time -f "povray: %e s wall, %U s user" nice povray +I$$< +O$(REF_TMP)/$(1)-raw.exr \
	  +W$$$$(($(3) * $(5))) +H$$$$(($(4) * $(5))) $(REF_POVRAY_FLAGS) >> $(REF_TMP)/$(1).log 2>&1 || \
	  { tail -n 20 $(REF_TMP)/$(1).log; exit 1; }
	oiiotool $(REF_TMP)/$(1)-raw.exr --resize:filter=box $(3)x$(4) -d half -o $(REF_TMP)/$(1).exr
	grep -v -e '^  *[0-9.]*%' -e 'Rendered [0-9]* of' -e 'cannot open the user configuration' $(REF_TMP)/$(1).log > $(call ref_path,$(1)).log
	mv $(REF_TMP)/$(1).exr $$@
endef

REF_SMALL := cornell-direct-129x96 cornell-fast-128x96 cornell-nocaustic-128x96 caustic-fast-128x96 caustic-reference-128x96 caustic-nocaustic-128x96 cornell-fast-16x12 \
             cornell-direct-256x192 cornell-fast-256x192 cornell-reference-256x192
REF_LARGE := cornell-reference-1024x768 cornell-reference-2x2-1024x768 cornell-fast-1024x768 cornell-fast-2x2-1024x768

# direct light only, for the per-pixel check: an odd width and a 3x3 grid, so
# that no sample ray hits a room edge exactly (the camera is centred in the
# room, so with even sample counts the four corner edges pass exactly through
# sample rays and either surface is a valid hit)
$(eval $(call ref_render,cornell-direct-129x96,$(REF_SCENE),129,96,3,--no-radiosity --no-photons,))
$(eval $(call ref_render,cornell-fast-128x96,$(REF_SCENE),128,96,2,--quality fast,))
# negative control: the glass caustic missing (the glass no photon target,
# its shadow kept by the shadow-only proxy), an option of the exporter
# (export-pov --no-glass-caustics; its SDL is reference/cornell/cornell-nocaustic-128x96.pov)
REF_NOCAUSTIC := --no-glass-caustics
$(eval $(call ref_render,cornell-nocaustic-128x96,$(REF_SCENE),128,96,2,--quality fast $(REF_NOCAUSTIC),))
$(eval $(call ref_render,cornell-fast-16x12,$(REF_SCENE),16,12,2,--quality fast,))
$(eval $(call ref_render,cornell-direct-256x192,$(REF_SCENE),256,192,2,--no-radiosity --no-photons,))
$(eval $(call ref_render,cornell-fast-256x192,$(REF_SCENE),256,192,2,--quality fast,))
$(eval $(call ref_render,cornell-reference-256x192,$(REF_SCENE),256,192,2,--quality reference,))
$(eval $(call ref_render,cornell-reference-1024x768,$(REF_SCENE),1024,768,1,--quality reference,))
# the same with the renders' own 2x2 subpixel rays (F = 2: rendered at
# 2048x1536 and box-downsampled), so that per-pixel metrics are valid against it
$(eval $(call ref_render,cornell-reference-2x2-1024x768,$(REF_SCENE),1024,768,2,--quality reference,))
# the same pixels at fast quality: its difference from the reference-quality
# render is the reference's own floor in the table's error columns
$(eval $(call ref_render,cornell-fast-1024x768,$(REF_SCENE),1024,768,1,--quality fast,))
# and the fast preset with the 2x2 subpixel rays: the floor of the 2x2
# reference (experiments/studies.py's pov_reference pairs each reference with the fast render
# of its own sampling)
$(eval $(call ref_render,cornell-fast-2x2-1024x768,$(REF_SCENE),1024,768,2,--quality fast,))

# The caustic scene (scenes/caustic.scene): the paper's room with the glass
# sphere lifted off the floor and moved back, so that its caustic lies in
# view (in cornell.scene it lies almost entirely under the sphere, hidden
# from the camera). Until the scene was promoted to scenes/ it was generated
# here as reference/caustic.scene; the images did not change.
REF_CAUSTIC := scenes/caustic.scene
$(eval $(call ref_render,caustic-fast-128x96,$(REF_CAUSTIC),128,96,2,--quality fast,))
$(eval $(call ref_render,caustic-reference-128x96,$(REF_CAUSTIC),128,96,2,--quality reference,))
$(eval $(call ref_render,caustic-nocaustic-128x96,$(REF_CAUSTIC),128,96,2,--quality fast $(REF_NOCAUSTIC),))

# The scenes that stress the method (scenes/slabs, library, tworooms;
# reference/README.md, "More scenes"): direct light only for the per-pixel
# check, the fast preset and reference quality for the full image. Their
# rectangles become boxes 1e-7 of the diagonal thick (0.45 um), not the
# default 1e-3 (4.5 mm), which closes the millimetre gaps of slabs.scene and
# the library's books (measured: reference/README.md).
REF_THIN := --rect-thickness 1e-7
define ref_scene
$(eval $(call ref_render,$(1)-direct-129x96,scenes/$(1).scene,129,96,3,--no-radiosity --no-photons $(REF_THIN),))
$(eval $(call ref_render,$(1)-fast-128x96,scenes/$(1).scene,128,96,2,--quality fast $(REF_THIN),))
$(eval $(call ref_render,$(1)-reference-128x96,scenes/$(1).scene,128,96,2,--quality reference $(REF_THIN),))
endef
$(foreach s,slabs library tworooms,$(eval $(call ref_scene,$(s))))
# tworooms.scene is lit through many bounces, and POV-Ray adds no light
# beyond about 8 (reference/README.md): its tests compare 2 bounces, ours
# rendered with --photon-depth 3
$(eval $(call ref_render,tworooms-b2-fast-128x96,scenes/tworooms.scene,128,96,2,--quality fast --bounces 2 $(REF_THIN),))
$(eval $(call ref_render,tworooms-b2-reference-128x96,scenes/tworooms.scene,128,96,2,--quality reference --bounces 2 $(REF_THIN),))
REF_SMALL += $(foreach s,slabs library tworooms,$(s)-direct-129x96 $(s)-fast-128x96 $(s)-reference-128x96) \
             tworooms-b2-fast-128x96 tworooms-b2-reference-128x96

reference-small: $(foreach n,$(REF_SMALL),$(call ref_path,$(n)).exr)
reference: reference-small $(foreach n,$(REF_LARGE),$(call ref_path,$(n)).exr)

# ---- pbrt-v3 references (reference/pbrt/README.md) ----
# SCENE:BDPT_SPP:SEEDS for each scene (seeds 1..SEEDS, PBRT_SEED); every seed is
# BDPT to 24 bounces plus the path tracer for 25-64 (reference/pbrt/render.sh),
# written to reference/SCENE/SCENE-pbrt-bdpt-256x192-seedK.{exr,log}.
# pbrt is not a Debian package: without it (PBRT=/path/to/pbrt or on PATH)
# the target refuses, and nothing else needs it.
# (two seeds each: what is committed and what reference/pbrt/agreement.md
# compares; more fitted no session's time on a loaded machine)
REF_PBRT_SCENES := cornell:64:2 tworooms:64:2 caustic:16:2 slabs:16:2 library:16:2
REF_PBRT_PATH_SPP := 64
.PHONY: reference-pbrt
reference-pbrt: $(BUILD)/photonmap
	@pbrt="$${PBRT:-$$(command -v pbrt || true)}"; \
	if [ -z "$$pbrt" ] || [ ! -x "$$pbrt" ]; then \
	  echo "make reference-pbrt: pbrt-v3 not found; build it as reference/pbrt/README.md says and run make reference-pbrt PBRT=/path/to/pbrt" >&2; exit 1; fi; \
	for s in $(REF_PBRT_SCENES); do scene=$${s%%:*}; r=$${s#*:}; spp=$${r%%:*}; n=$${r#*:}; for k in $$(seq 1 $$n); do \
	  PBRT="$$pbrt" bash reference/pbrt/render.sh $$scene 256 192 $$spp $(REF_PBRT_PATH_SPP) $$k || exit 1; \
	done; done
