"""Frames of a rollout, rendered from the full welded scene.

The renderer is Drake's `RenderEngineVtk` (it works headless on this machine), added to a fresh
context of the "held" planning model: that model holds every scene instance, the robot, and the
target on its 6-dof HELD_JOINT, so any simulated state is shown by setting the robot's joints
and placing the object at its simulated world pose through that joint
(X_GO = X_WG(q)^-1 X_WO). Images come from `QueryObject.RenderColorImage` (RGBA, 8 bit).

The animation is a flipbook: `flipbook_html` writes one self-contained HTML page holding the
frames as base64 PNGs and a few lines of JavaScript that play them (no server, no network).
"""

import base64
import math

import numpy as np
from pydrake.geometry import (
    ClippingRange,
    ColorRenderCamera,
    MakeRenderEngineVtk,
    RenderCameraCore,
    RenderEngineVtkParams,
)
from pydrake.math import RigidTransform, RotationMatrix
from pydrake.systems.sensors import CameraInfo

from drake_bridge.policy.output import png_bytes

IMAGE_SIZE = (480, 360)
FOV_Y_RAD = 0.9


class FrameRenderer:
    """Renders states (robot joint values, X_WO) of `model` (a "held" PlanningModel) from a
    camera at X_WC."""

    def __init__(self, model, X_WC):
        assert model.mode == "held"
        self.model = model
        self.context = model.diagram.CreateDefaultContext()
        scene_graph = model.diagram.scene_graph()
        scene_graph.AddRenderer(scene_graph.GetMyMutableContextFromRoot(self.context), "vtk",
                                MakeRenderEngineVtk(RenderEngineVtkParams()))
        self.plant_context = model.plant.GetMyMutableContextFromRoot(self.context)
        core = RenderCameraCore("vtk", CameraInfo(IMAGE_SIZE[0], IMAGE_SIZE[1], FOV_Y_RAD),
                                ClippingRange(0.05, 30.0), RigidTransform())
        self.camera = ColorRenderCamera(core, False)
        self.world = scene_graph.world_frame_id()
        self.X_WC = X_WC

    def render(self, robot_values, X_WO):
        """An H x W x 4 uint8 image of the state."""
        model, plant = self.model, self.model.plant
        q = model.q_from(robot_values)
        plant.SetPositions(self.plant_context, q)
        X_WG = model.grasp_frame.CalcPoseInWorld(self.plant_context)
        plant.SetPositions(self.plant_context, model.with_held_pose(q, X_WG.inverse() @ X_WO))
        query = plant.get_geometry_query_input_port().Eval(self.plant_context)
        image = query.RenderColorImage(self.camera, self.world, self.X_WC)
        return np.array(image.data, copy=True)


def look_at(p_eye, p_target):
    """X_WC of a camera at p_eye looking at p_target (Drake's camera frame: +z forward, +x
    right, +y down in the image)."""
    z = np.asarray(p_target, dtype=float) - p_eye
    z /= np.linalg.norm(z)
    x = np.cross(z, [0.0, 0.0, 1.0])
    if np.linalg.norm(x) < 1e-6:
        x = np.array([1.0, 0.0, 0.0])
    x /= np.linalg.norm(x)
    y = np.cross(z, x)
    return RigidTransform(RotationMatrix(np.column_stack([x, y, z])), p_eye)


def camera_pose(p_focus, base_xy, room_bounds=None):
    """A view of p_focus from beside the robot: 1.4 m away horizontally, across the base ->
    focus direction and 0.5 m behind the focus (on whichever side stays further inside
    `room_bounds` ((x0, y0), (x1, y1)) when given), 1.0 m above the focus."""
    d = np.asarray(p_focus[:2]) - np.asarray(base_xy)
    d = d / (np.linalg.norm(d) + 1e-12)
    best = None
    for sign in (1.0, -1.0):
        side = sign * np.array([-d[1], d[0]])
        eye_xy = np.asarray(p_focus[:2]) + 1.4 * side - 0.5 * d
        margin = math.inf
        if room_bounds is not None:
            (x0, y0), (x1, y1) = room_bounds
            margin = min(eye_xy[0] - x0, x1 - eye_xy[0], eye_xy[1] - y0, y1 - eye_xy[1])
        if best is None or margin > best[0]:
            best = (margin, eye_xy)
    eye = np.array([best[1][0], best[1][1], p_focus[2] + 1.0])
    return look_at(eye, p_focus)


def flipbook_html(title, frames, fps):
    """A self-contained HTML page playing `frames` (list of (caption, RGBA array)) at fps."""
    images = ",\n".join(
        '["%s", "data:image/png;base64,%s"]' % (caption.replace('"', "'"),
                                                base64.b64encode(png_bytes(rgba)).decode())
        for caption, rgba in frames)
    return f"""<!DOCTYPE html>
<html><head><meta charset="utf-8"><title>{title}</title></head>
<body style="font-family: sans-serif">
<h3>{title}</h3>
<img id="frame" style="border: 1px solid #888"><div id="caption"></div>
<button onclick="playing = !playing">play / pause</button>
<input id="slider" type="range" min="0" max="{len(frames) - 1}" value="0"
       oninput="playing = false; show(+this.value)">
<script>
const frames = [
{images}
];
let k = 0, playing = true;
function show(i) {{
  k = i;
  document.getElementById("frame").src = frames[k][1];
  document.getElementById("caption").textContent = frames[k][0];
  document.getElementById("slider").value = k;
}}
show(0);
setInterval(() => {{ if (playing) show((k + 1) % frames.length); }}, {int(1000 / fps)});
</script>
</body></html>
"""
