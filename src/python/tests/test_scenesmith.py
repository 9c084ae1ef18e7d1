"""The Python package `scenesmith` (src/python) with pydrake: generate a scene in-process,
load it into a MultibodyPlant through Scene.add_to_plant, evaluate and export it; refused
prompts and bad directories raise the package's exceptions with the CLI's messages; the GIL
is released while a scene is generated."""

import json
import threading
import time

import pytest

import scenesmith
from pydrake.all import AddMultibodyPlantSceneGraph, DiagramBuilder, Parser, Simulator

PROMPT = "a bedroom with a bed and a nightstand with a lamp on it"


@pytest.fixture(scope="module")
def generated(tmp_path_factory):
    """One scene, generated on a thread while this thread keeps ticking: the longest pause
    between ticks says whether the GIL was held."""
    out = tmp_path_factory.mktemp("scene") / "bedroom"
    box = {}

    def work():
        box["scene"] = scenesmith.generate(PROMPT, out, seed=3, render=False, stb=False,
                                           exports="glb")

    thread = threading.Thread(target=work)
    ticks = [time.monotonic()]
    thread.start()
    while thread.is_alive():
        time.sleep(0.01)
        ticks.append(time.monotonic())
    thread.join()
    gaps = [b - a for a, b in zip(ticks, ticks[1:])]
    return box["scene"], max(gaps), ticks[-1] - ticks[0]


def test_generate_returns_the_scene_and_releases_the_gil(generated):
    scene, longest_pause, total = generated
    assert total > 2.0, "a scene takes seconds"
    # Held GIL: this thread would have stopped for the whole run.
    assert longest_pause < 0.5, f"the main thread paused {longest_pause:.2f} s of {total:.1f} s"
    assert scene.package_name == "bedroom"
    assert {"directives", "package_xml", "scene_json", "glb"} <= set(scene.paths)
    assert "mjcf" not in scene.paths, "only the GLB export was asked for"
    cats = {o["category"] for o in scene.objects}
    assert {"bed", "nightstand"} <= cats, cats
    assert scene.summary["metrics"]["col"]["percent"] == 0.0
    assert scene.metrics == json.loads(scene.paths["metrics"].read_text())


def test_add_to_plant_loads_every_object_in_drake(generated):
    scene = generated[0]
    builder = DiagramBuilder()
    plant, _ = AddMultibodyPlantSceneGraph(builder, 0.001)
    parser = Parser(plant)
    instances = scene.add_to_plant(plant, parser)
    plant.Finalize()
    ids = {o["id"] for o in scene.objects}
    assert set(instances) == ids, set(instances) ^ ids
    free = {o["id"] for o in scene.objects if not o["welded"]}
    floating_bodies = [plant.get_body(i) for i in plant.GetFloatingBaseBodies()]
    floating = {plant.GetModelInstanceName(b.model_instance()) for b in floating_bodies}
    assert floating == free
    # The loaded scene simulates: nothing flies off in 0.2 s.
    diagram = builder.Build()
    sim = Simulator(diagram)
    sim.AdvanceTo(0.2)
    ctx = plant.GetMyContextFromRoot(sim.get_context())
    for b in floating_bodies:
        assert abs(plant.EvalBodySpatialVelocityInWorld(ctx, b).translational()[2]) < 0.5


def test_a_second_parser_package_is_not_added_twice(generated):
    scene = generated[0]
    builder = DiagramBuilder()
    plant, _ = AddMultibodyPlantSceneGraph(builder, 0.0)
    parser = Parser(plant)
    parser.package_map().AddPackageXml(str(scene.paths["package_xml"]))
    assert len(scene.add_to_plant(plant, parser)) == len(scene.objects)


def test_a_package_name_mapped_to_another_directory_is_refused(generated, tmp_path):
    scene = generated[0]
    other = tmp_path / scene.package_name
    other.mkdir()
    (other / "package.xml").write_text(scene.paths["package_xml"].read_text())
    builder = DiagramBuilder()
    plant, _ = AddMultibodyPlantSceneGraph(builder, 0.0)
    parser = Parser(plant)
    parser.package_map().AddPackageXml(str(other / "package.xml"))
    with pytest.raises(scenesmith.ScenesmithError, match="already maps package"):
        scene.add_to_plant(plant, parser)


def test_evaluate_and_export_write_their_files(generated):
    scene = generated[0]
    metrics = scenesmith.evaluate(scene.dir, stb=False)
    assert metrics["col"]["percent"] == 0.0
    assert metrics["stb"] is None
    written = scenesmith.export(scene.dir, "mjcf")
    assert [w["format"] for w in written] == ["mjcf"]
    assert (scene.dir / written[0]["main_file"]).is_file()
    again = scenesmith.load(scene.dir)
    assert "mjcf" in again.paths and again.summary is None


def test_errors_raise_the_package_exceptions_with_the_cli_messages(tmp_path):
    with pytest.raises(scenesmith.PromptError, match="empty"):
        scenesmith.generate("   ", tmp_path / "a")
    with pytest.raises(scenesmith.PromptError, match="understood no room"):
        scenesmith.generate("blorptastic frumious wabe", tmp_path / "b")
    assert issubclass(scenesmith.PromptError, scenesmith.ScenesmithError)
    with pytest.raises(scenesmith.ScenesmithError, match="not a scene directory"):
        scenesmith.load(tmp_path)
    with pytest.raises(scenesmith.ScenesmithError, match="evaluating"):
        scenesmith.evaluate(tmp_path, stb=False)
    with pytest.raises(scenesmith.ScenesmithError, match="unknown|format"):
        scenesmith.export(tmp_path, "obj")
    assert not (tmp_path / "a").exists() and not (tmp_path / "b").exists()
