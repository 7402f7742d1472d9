"""Writes docs/robustness.md: every robustness case, what it checks, and its result in a fresh ctest run.

    /usr/bin/python3.11 tests/robustness/report.py [--build build]      (make robustness-report)
"""

import argparse
import datetime
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

# ctest name (or prefix) -> (case, what it checks)
CASES = [
    ("Fuzz.RandomScenesRenderFinite", "1,000 random scenes (sizes 1e-4 to 1e4, degenerate triangles, negative scales, "
     "every material and light type, strengths up to 1e6, every integrator)",
     "each finishes with finite, non-negative pixels and no dropped non-finite samples"),
    ("Fuzz.RegressionSeeds", "seeds that once failed", "they keep passing"),
    ("SelfIntersection.NoSelfHitsFromTrianglesAtAnyScale", "rays leaving triangles at scales 1e-4 to 1e4, far from "
     "the origin", "no ray re-hits its own triangle (scale-relative origin offset)"),
    ("FarFromOrigin.RoomAt1e5RendersLikeAtTheOrigin", "a lit room moved 1e5 units from the origin",
     "same image as at the origin within noise (camera-world space), no speckle"),
    ("Energy.ClosedWhiteBoxTerminates", "albedo 1.0 closed box, max_bounces 1024",
     "paths end (roulette cannot, the bounce limit does); finite result"),
    ("Energy.TinyMillionStrengthEmitterStaysFinite", "a 2e-4 wide emitter of strength 1e6 and a 1e6 W point light",
     "no NaN or Inf"),
    ("BadInput.HugeResolutionIsRefusedBeforeAllocation", "a 1,000,000² render", "refused with the memory it needs"),
    ("BadInput.ZeroResolutionIsRefused", "0 × 10 pixels", "refused, naming the resolution"),
    ("BadInput.MeshWithoutFacesRendersNothingForIt", "a mesh with no faces", "skipped; the rest renders"),
    ("BadInput.SceneWithoutLightsWarnsAndIsBlack", "no lights, black world", "renders black with a warning"),
    ("BadInput.CancelDuringTheBvhBuildReturnsQuickly", "cancel while a 1M-triangle BVH builds",
     "returns within 2 s, no error"),
    ("Coplanar.AreaLightInTheCeilingPlaneMatchesTheLightJustBelowIt", "a Blender area light lying exactly in the "
     "ceiling's plane, at scales 1e-3, 1 and 1e3 and 3e4 units from the origin",
     "same image as with the light 1e-4 below the ceiling: no pixel apart by more than 6σ, the light's mean within "
     "4σ (no speckle)"),
    ("Coplanar.EmissiveQuadOnTheCeilingShowsNoSpeckle", "an emissive quad coplanar with a ceiling quad (same scales)",
     "every pixel inside the emitter sees only the emitter (an exact colour test), no local-median outliers, same "
     "image as the quad 1e-4 below"),
    ("Coplanar.OverlappingQuadsOfTwoColoursShowOneOfThemEverywhere", "two overlapping coplanar quads, pure red and "
     "pure green: face-on, at 18° grazing, rotated off the axes, at 4 scales and offsets",
     "every overlap pixel shows one colour, the same one everywhere (no z-fighting)"),
    ("Coplanar.ParallelQuadsAGapOf1e4ApartStayDistinct", "a quad 1e-4 (of the scene's size) in front of another "
     "that would win a tie, face-on and grazing, at 4 scales and offsets",
     "every pixel shows the front quad: the tie-break never merges distinct surfaces"),
    ("ScaleInvariance.ARoomRendersTheSameFrom1e5To1e4", "a closed room with a thin shelf at sizes 1e-5, 1e-4, 1e-3, "
     "1e2 and 1e4", "same image as at size 1 (6σ per pixel, 4σ in the mean): no light through the shelf"),
    ("Coplanar.SpeckleMeasureFindsAnInjectedOutlier", "the speckle measure (local median, 6σ plus local structure)",
     "finds a single injected outlier, and nothing in a clean render"),
    ("ShadingNormals.LowPolySmoothObjectsShadeSmoothlyOutsideTheTerminatorBand", "low-poly smooth-shaded spheres "
     "(12×6, 8×4) and a 10-sided cylinder under a sun from the side",
     "smooth-shading radiance wherever facet and shading normals agree, exactly black where the light is behind, "
     "dark only in the terminator band, whose smooth shading is ≤ sin δ of full brightness (no faceting)"),
    ("ShadingNormals.WhiteFurnaceWithSmoothShadingCreatesNoEnergy", "white furnace: albedo-1 low-poly smooth objects "
     "(diffuse and GGX) and a ground with shading normals tilted ±35°, seen at grazing angles",
     "every pixel ≤ 1 within 6σ, the mean ≤ 1 within 4σ, no NaN"),
    ("ShadingNormals.NoLightLeaksIntoAClosedSmoothShadedEnclosure", "the camera inside a closed low-poly smooth box "
     "or sphere; point, soft point, sun and area lights and a white world outside",
     "exactly black inside (and bright without the walls)"),
    ("LightsInsideClosedObjects.StayInvisibleFromOutside", "point (soft, on the floor), spot, area and emissive-mesh "
     "lights inside a closed box (flat and smooth-shaded)", "exactly black outside, no NaN"),
    ("PointLightOnASurface.StaysFiniteAndLightsTheRestAsJustAboveIt", "a point light on a face and on a vertex of a "
     "floor, radius 0 and 0.1", "finite, no NaN; the rest lit as by the light 1e-4 above it (6σ per pixel)"),
    ("NegativeScale.MirroredObjectsRenderLikeTheOriginals", "glass and diffuse low-poly smooth spheres mirrored along "
     "one and three axes, flattened and instanced",
     "same image as unmirrored (6σ per pixel, 4σ in the mean); normals point out"),
    ("Memory.SceneTooLargeForTheLimitIsRefusedNamingTheBiggestMesh", "a scene over the memory limit",
     "refused before anything is built, naming the biggest mesh, its triangles and the memory it needs"),
    ("Memory.ResolutionTooLargeForTheLimitIsRefusedBeforeAllocation", "a 20,000² film over the memory limit",
     "refused before allocation, with the memory it needs"),
    ("Memory.TheDefaultLimitIsTheAvailableMemory", "no memory limit set",
     "the machine's MemAvailable is the limit; a normal scene fits"),
    ("Memory.EstimateBoundsThePeakOfARealBuild", "the memory estimate against the measured peak of building a "
     "261k-triangle sphere and a 250k-triangle soup", "measured ≤ estimate ≤ 3 × measured"),
    ("robustness_sessions", "start → cancel and start → finish, 50 times each after warm-up",
     "always finite images; resident memory grows < 5 %"),
    ("robustness_blender_bad_input", "through Blender: empty scene, NaN vertex, infinite scale, zero scale, mesh "
     "without faces, n-gons and non-manifold meshes, no lights, unsupported node, zero resolution, a scene too large "
     "for a lowered memory limit, cancel during export, 20 renders in a row",
     "an error naming the object and the problem, or a render with a warning"),
    ("robustness_blender_cancel", "through the add-on's render loop: Esc during export, during a 1.3M-triangle BVH "
     "build, during rendering; then 60 cancel/render cycles",
     "a result always handed back (the partial image when rendering), no crash or hang, back within 0.1 s while "
     "rendering and 1 s while building; resident memory grows < 5 %"),
    ("python_native", "bad arrays and params through the Python module; cancel latency",
     "ValueError naming the array / index / key; cancel within 100 ms"),
]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=str(ROOT / "build"))
    ap.add_argument("--out", default=str(ROOT / "docs" / "robustness.md"))
    a = ap.parse_args()
    build = Path(a.build).resolve()
    junit = build / "robustness-junit.xml"
    subprocess.run(["ctest", "-R", "Fuzz|SelfIntersection|FarFromOrigin|Energy|BadInput|Coplanar|ShadingNormals|"
                    "LightsInsideClosedObjects|PointLightOnASurface|NegativeScale|Memory|ScaleInvariance|robustness_|"
                    "python_native",
                    "--output-junit", str(junit)], cwd=build, check=False)
    results = {}
    for case in ET.parse(junit).getroot().iter("testcase"):
        failed = case.find("failure") is not None or case.get("status") == "fail"
        skipped = case.find("skipped") is not None
        results[case.get("name")] = "skipped" if skipped else ("**FAIL**" if failed else "pass")
    lines = ["# Robustness", "",
             "Generated by `make robustness-report` (`tests/robustness/report.py`) from a ctest run on "
             f"{datetime.date.today()}; the cases live in `tests/robustness/` and run in `make test`. "
             "`make fuzz` runs 20,000 random scenes; `make test-sanitize` runs the C++ suites and a render under "
             "AddressSanitizer and UndefinedBehaviorSanitizer.", "",
             "Guards that every render has: non-finite or negative samples never reach the film (they are dropped "
             "and counted, and the count is reported as a warning); debug builds throw where one arises instead.", "",
             "| case | what it checks | result |", "|---|---|---|"]
    for name, case, checks in CASES:
        lines.append(f"| {case} | {checks} | {results.get(name, 'not run')} |")
    Path(a.out).write_text("\n".join(lines) + "\n")
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
