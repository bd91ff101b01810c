# tools/lib/sweep.sh: the validation sweep's runs, shared by tools/debian13 (Debian 13's layer)
# and tools/validate-newest (the newest layer): sourced, not run.
#
# sweep_runs FN: calls `FN ARGS...` once per run, ARGS being vkocean's arguments for it (FN adds
# --validation and whatever else it checks): every --view, both --waves models, each water
# --geometry of SWEEP_GEOMETRIES (default: both; tools/swiftshader: clipmap, the device has no
# tessellation) and every --quality (high without the foam simulation near the camera; low with
# the edge-directed upscale, which a CPU device does not draw by default; medium with natural
# slicks over half the sea, which the default 10 m/s wind has none of) headless at 160x90
# for 3 frames, the storm at medium (the
# spray flies, lands and adds to the foam levels: about 9,000 puffs, 100 landing a frame), the
# view from under the water over the shallows (the light shafts' pass, the floor mirrored
# outside Snell's window) and from a camera half in the water (the waterline's pipeline), and
# bench fft at sizes 64 and 128.
sweep_runs() {
    local fn=$1 view waves geometry
    local small=(--headless --size 160x90 --frames 3)
    for view in final reflection refraction displacement normals foam dudv wireframe crests \
        triangles; do
        "$fn" "${small[@]}" --view "$view"
    done
    for waves in fft gerstner; do
        "$fn" "${small[@]}" --waves "$waves"
    done
    for geometry in ${SWEEP_GEOMETRIES:-tessellated clipmap}; do
        "$fn" "${small[@]}" --geometry "$geometry"
    done
    # --quality high without the foam simulation near the camera: its 32 warm-up steps go in
    # the first frame's one submission, which under GPU-assisted validation on lavapipe took
    # longer than vkocean's 60 s GPU wait at high (its levels are the same at medium, which
    # runs it).
    "$fn" "${small[@]}" --quality low --upscale edge
    "$fn" "${small[@]}" --quality medium --slicks 0.5
    "$fn" "${small[@]}" --quality high --foam-sim off
    "$fn" "${small[@]}" --preset storm --quality medium
    "$fn" "${small[@]}" --preset calm --camera=-140,-3,-860 --look-at=-150,3,-860
    "$fn" "${small[@]}" --preset calm --wind-speed 1 --camera=-102,0,-582 --look-at=-60,0,-600
    # The height queries' readback, floating bodies and a boat's wake (its 400 warm-up steps).
    "$fn" "${small[@]}" --bodies 4 --boat 3,30
    "$fn" bench fft --sizes 64,128 --runs 3
}
