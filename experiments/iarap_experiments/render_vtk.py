"""Renders side-by-side pictures of meshes with VTK (Debian's python3-vtk9), one PNG per job file.

Run as a script under an X server (the driver uses `xvfb-run -a`, VTK 9.1 in Debian renders through GLX):
    xvfb-run -a /usr/bin/python3 render_vtk.py JOB.json
JOB.json: {"out": "pic.png", "panel_size": [w, h], "view": {"direction": [x, y, z], "up": [x, y, z],
           "zoom": 1.0}, "panels": [{"title": "...", "layers": [LAYER, ...]}, ...]}
LAYER: {"obj": "mesh.obj", "kind": "surface" | "lines", "color": [r, g, b], "edges": false,
        "highlight": [vertex indices: small spheres, and their faces painted], "highlight_color": [r, g, b],
        "line_width": 1.0, "opacity": 1.0}
Every panel gets the same camera, framed on the union of all panels' bounds, so panels compare 1:1.
"""
from __future__ import annotations

import json
import sys

import numpy as np
import vtk
from vtk.util import numpy_support

from mesh_io import read_obj_elements  # this script's folder is on sys.path


def _cells(polygons: list[list[int]]) -> vtk.vtkCellArray:
    cells = vtk.vtkCellArray()
    for polygon in polygons:
        cells.InsertNextCell(len(polygon))
        for index in polygon:
            cells.InsertCellPoint(index)
    return cells


def layer_actors(layer: dict) -> tuple[list, np.ndarray]:
    V, faces, lines = read_obj_elements(layer["obj"])
    points = vtk.vtkPoints()
    points.SetData(numpy_support.numpy_to_vtk(V, deep=True))
    poly = vtk.vtkPolyData()
    poly.SetPoints(points)
    color = np.array(layer.get("color", [0.85, 0.85, 0.8]), dtype=np.float64)
    actor = vtk.vtkActor()
    if layer.get("kind", "surface") == "lines":
        poly.SetLines(_cells(lines))
        mapper = vtk.vtkPolyDataMapper()
        mapper.SetInputData(poly)
        actor.SetMapper(mapper)
        actor.GetProperty().SetColor(*color)
        actor.GetProperty().SetLineWidth(layer.get("line_width", 1.0))
        actor.GetProperty().LightingOff()
        return [actor], V
    poly.SetPolys(_cells(faces))
    # Constrained vertices: their faces (all three corners constrained) are painted, and each vertex gets a
    # small sphere, so boundary rings of constraints show too; vertex colours would bleed into neighbours.
    highlight = np.asarray(layer.get("highlight", []), dtype=np.int64)
    highlight_color = layer.get("highlight_color", [0.85, 0.1, 0.1])
    face_rgb = np.tile(color, (len(faces), 1))
    if len(highlight) and len(faces):
        marked = np.zeros(len(V), dtype=bool)
        marked[highlight] = True
        F = np.asarray(faces, dtype=np.int64)
        face_rgb[marked[F].all(axis=1)] = highlight_color
    colors = numpy_support.numpy_to_vtk((face_rgb * 255).astype(np.uint8), deep=True)
    colors.SetName("colors")
    poly.GetCellData().SetScalars(colors)
    normals = vtk.vtkPolyDataNormals()
    normals.SetInputData(poly)
    normals.SetSplitting(layer.get("split_normals", False))
    normals.SetFeatureAngle(60)
    normals.ConsistencyOn()
    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputConnection(normals.GetOutputPort())
    mapper.SetColorModeToDirectScalars()
    mapper.SetScalarModeToUseCellData()
    actor.SetMapper(mapper)
    prop = actor.GetProperty()
    prop.SetSpecular(0.15)
    prop.SetSpecularPower(20)
    prop.SetOpacity(layer.get("opacity", 1.0))
    if layer.get("edges", False):
        prop.EdgeVisibilityOn()
        prop.SetEdgeColor(*layer.get("edge_color", [0.25, 0.25, 0.3]))
        prop.SetLineWidth(layer.get("line_width", 1.0))
    if layer.get("flat", False):
        prop.SetInterpolationToFlat()
    actors = [actor]
    if len(highlight):
        actors.append(_sphere_glyphs(V[highlight], layer.get("sphere_radius", 0.004) * float(
            np.linalg.norm(V.max(axis=0) - V.min(axis=0))), highlight_color))
    return actors, V


def _sphere_glyphs(P: np.ndarray, radius: float, color) -> vtk.vtkActor:
    points = vtk.vtkPoints()
    points.SetData(numpy_support.numpy_to_vtk(np.ascontiguousarray(P), deep=True))
    cloud = vtk.vtkPolyData()
    cloud.SetPoints(points)
    sphere = vtk.vtkSphereSource()
    sphere.SetRadius(radius)
    sphere.SetThetaResolution(8)
    sphere.SetPhiResolution(8)
    glyphs = vtk.vtkGlyph3D()
    glyphs.SetInputData(cloud)
    glyphs.SetSourceConnection(sphere.GetOutputPort())
    glyphs.ScalingOff()
    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputConnection(glyphs.GetOutputPort())
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetColor(*color)
    return actor


def render(job: dict) -> None:
    panel_w, panel_h = job.get("panel_size", [400, 400])
    panels = job["panels"]
    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(panel_w * len(panels), panel_h + 0)
    window.SetMultiSamples(8)
    all_points = []
    renderers = []
    for k, panel in enumerate(panels):
        renderer = vtk.vtkRenderer()
        renderer.SetViewport(k / len(panels), 0.0, (k + 1) / len(panels), 1.0)
        renderer.SetBackground(1.0, 1.0, 1.0)
        for layer in panel["layers"]:
            actors, V = layer_actors(layer)
            for actor in actors:
                renderer.AddActor(actor)
            all_points.append(V if not layer.get("frame_ignore", False) else np.empty((0, 3)))
        title = vtk.vtkTextActor()
        title.SetInput(panel.get("title", ""))
        title.GetTextProperty().SetFontSize(max(12, panel_h // 22))
        title.GetTextProperty().SetColor(0.1, 0.1, 0.1)
        title.GetTextProperty().SetJustificationToCentered()
        title.SetPosition(panel_w / 2, panel_h - max(12, panel_h // 22) - 8)
        renderer.AddActor2D(title)
        window.AddRenderer(renderer)
        renderers.append(renderer)
    frame = job.get("frame_points")
    P = np.asarray(frame, dtype=np.float64) if frame else np.vstack(all_points)
    lo, hi = P.min(axis=0), P.max(axis=0)
    center = 0.5 * (lo + hi)
    radius = 0.5 * float(np.linalg.norm(hi - lo))
    view = job.get("view", {})
    direction = np.asarray(view.get("direction", [0.0, 0.0, 1.0]), dtype=np.float64)
    direction /= np.linalg.norm(direction)
    up = view.get("up", [0.0, 1.0, 0.0])
    view_angle = 30.0
    distance = radius / np.sin(np.radians(view_angle / 2)) / view.get("zoom", 1.0)
    for renderer in renderers:
        camera = renderer.GetActiveCamera()
        camera.SetFocalPoint(*center)
        camera.SetPosition(*(center + distance * direction))
        camera.SetViewUp(*up)
        camera.SetViewAngle(view_angle)
        renderer.ResetCameraClippingRange()
        light_kit = vtk.vtkLightKit()
        light_kit.AddLightsToRenderer(renderer)
    window.Render()
    grab = vtk.vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.Update()
    writer = vtk.vtkPNGWriter()
    writer.SetFileName(job["out"])
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()


def main(argv: list[str]) -> int:
    for path in argv[1:]:
        with open(path, encoding="utf-8") as f:
            render(json.load(f))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
