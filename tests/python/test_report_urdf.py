"""Run.report of a URDF robot (issue 36 item 13): the links are drawn by their <visual>
geometry, and a link whose mesh is missing, drawn from its inertia, gives a UserWarning."""

import shutil
import warnings

import pytest

import lagrange
from conftest import SOURCE_DIR

ARM = SOURCE_DIR / "tests" / "io" / "urdf_visuals" / "visual_arm.urdf"


def test_a_missing_mesh_warns_once_per_link(tmp_path, monkeypatch):
    monkeypatch.setenv("ROS_PACKAGE_PATH", "")
    shutil.copy(ARM, tmp_path / "visual_arm.urdf")  # without its meshes/
    run = lagrange.load(str(tmp_path / "visual_arm.urdf")).simulate(t_end=0.1)
    with pytest.warns(UserWarning) as caught:
        run.report(str(tmp_path / "arm.html"))
    messages = sorted(str(w.message) for w in caught)
    assert len(messages) == 2, messages
    assert messages[0].startswith("link 'base': mesh 'meshes/plate.dae' not found")
    assert messages[1].startswith("link 'tool': mesh 'package://urdf_visuals/meshes/tip.stl'")


def test_meshes_beside_the_urdf_give_no_warning(tmp_path, monkeypatch):
    monkeypatch.setenv("ROS_PACKAGE_PATH", "")
    run = lagrange.load(str(ARM)).simulate(t_end=0.1)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        run.report(str(tmp_path / "arm.html"))
    assert '"type":"mesh"' in (tmp_path / "arm.html").read_text()
