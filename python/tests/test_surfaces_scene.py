"""Patches, tessellation and scenes through Python: the mesh's proven bound against surface
samples, watertightness of the welded teapot, scenes built and loaded, rendered and traced."""
import os

import numpy as np
import pytest

import casteljau as cj


def saddle():
    pts = np.zeros((3, 3, 3))
    for i in range(3):
        for j in range(3):
            pts[i, j] = [i / 2, j / 2, (i - 1) * (j - 1) * 0.5]
    return cj.Patch(pts)


def test_patch_eval_and_normal():
    p = saddle()
    assert p.degree == (2, 2)
    assert np.allclose(p.eval(0, 0), [0, 0, 0.5])
    assert np.allclose(p.eval(1, 0), [1, 0, -0.5])
    # z(u, v) = 0.5 (2u-1)(2v-1): normal at the centre is +z
    assert np.allclose(p.normal(0.5, 0.5), [0, 0, 1])


def test_tessellation_bound_and_arrays():
    p = saddle()
    mesh = cj.tessellate(p, tol=1e-3, measure=4)
    assert mesh.positions.shape[1] == 3 and mesh.triangles.shape[1] == 3
    assert mesh.triangles.dtype == np.uint32 and mesh.triangles.max() < len(mesh.positions)
    assert mesh.bound <= 1e-3 and 0 <= mesh.measured <= mesh.bound
    # every mesh vertex lies on the surface at its (u, v)
    for (u, v), x in zip(mesh.uvs[::7], mesh.positions[::7]):
        assert np.allclose(p.eval(u, v), x, atol=1e-15)
    uni = cj.tessellate(p, uniform=4, weld=False)
    assert len(uni.triangles) == 32
    print(f"adaptive: {len(mesh.triangles)} triangles, bound {mesh.bound:.3g}, "
          f"measured {mesh.measured:.3g}")


def test_teapot_welded_is_closed_where_the_teapot_is():
    patches = cj.teapot()
    assert len(patches) == 32
    mesh = cj.tessellate(patches, tol=1e-2)
    edges = {}
    for tri in mesh.triangles:
        for a, b in ((tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0])):
            key = (min(a, b), max(a, b))
            edges[key] = edges.get(key, 0) + 1
    boundary = sum(1 for n in edges.values() if n == 1)
    print(f"teapot: {len(mesh.triangles)} triangles, {boundary} boundary edges")
    # The Utah teapot has no bottom and its lid is separate: some boundary is real, but a
    # cracked (unwelded) mesh would have every patch edge open: thousands.
    unwelded = cj.tessellate(patches, tol=1e-2, weld=False)
    assert len(unwelded.positions) > len(mesh.positions)
    assert boundary < len(edges) // 20


def build_scene():
    s = cj.Scene()
    s.set_camera(eye=(0, 0, 6), look_at=(0, 0, 0))
    s.set_settings(width=64, height=48, spp=1, background=(0, 0, 0.25))
    s.add_light("ambient", intensity=0.2)
    s.add_light("point", position=(4, 4, 6), intensity=1.0)
    red = s.add_material(color=(0.9, 0.1, 0.1))
    s.add_sphere((0, 0, 0), 1.5, red)
    return s


def test_built_scene_renders_and_traces():
    s = build_scene()
    s.check()
    img = s.render()
    assert img.shape == (48, 64) and img.rgba.dtype == np.float32
    centre = img.rgba[24, 32]
    corner = img.rgba[0, 0]
    print("raster centre", centre, "corner", corner)
    assert centre[0] > 2 * centre[2] and centre[3] == 1.0  # red sphere, covered
    assert corner[3] == 0.0 and abs(corner[2] - 0.25) < 1e-6  # background
    assert img.ids[24, 32] == 1 and img.ids[0, 0] == 0
    assert img.depth[24, 32] < 1.0 and img.depth[0, 0] == 1.0
    # the light is up and to the right: the upper right of the sphere is brighter (top row first)
    assert img.rgba[14, 40, 0] > img.rgba[34, 24, 0]
    tr = s.trace(seed=3)
    assert tr.shape == (48, 64)
    assert np.array_equal(tr.ids, img.ids) or np.mean(tr.ids == img.ids) > 0.97
    srgb = img.srgb8()
    assert srgb.dtype == np.uint8 and srgb.shape == (48, 64, 4)
    assert srgb[24, 32, 0] > srgb[24, 32, 2]


def test_patch_object_in_scene():
    s = cj.Scene()
    s.set_camera(eye=(0.5, -2.5, 2.5), look_at=(0.5, 0.5, 0))
    s.set_settings(width=40, height=40)
    s.add_light("directional", direction=(0, 0, -1))
    m = s.add_material(color=(0.2, 0.8, 0.2), two_sided=True)
    s.add_patches(saddle(), m)
    img = s.render()
    covered = np.count_nonzero(img.ids == 1)
    print("saddle covers", covered, "pixels")
    assert covered > 60
    assert img.ids[20, 20] == 1  # the patch is seen at the point looked at


def test_loaded_scene_and_errors(source_dir, tmp_path):
    s = cj.Scene.load(os.path.join(source_dir, "scenes", "quadrics.json"))
    img = s.render(width=80, height=60)
    assert img.shape == (60, 80)
    assert len(np.unique(img.ids)) > 2
    with pytest.raises(cj.CasteljauError) as e:
        cj.Scene.from_json('{"camera": {"eye": [0, 0, "x"]}}', name="bad.json")
    print("message:", e.value)
    assert "bad.json" in str(e.value)
    with pytest.raises(cj.CasteljauError) as e:
        build_scene().render(spp=3)
    assert "3" in str(e.value)
    s.save(tmp_path / "copy.json")
    again = cj.Scene.load(tmp_path / "copy.json")
    assert again.node_count == s.node_count
    assert np.array_equal(again.render(width=80, height=60).rgba, img.rgba)
