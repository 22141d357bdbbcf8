"""ParaView's pvbatch as a peer: renders a PLY (from `lzb export`) along the cameras of an lzb
report and prints every frame's render time as JSON (rank 0). Run by runs/peers/run.py as
  xvfb-run -a mpirun -n RANKS pvbatch runs/peers/pvbatch_render.py MESH.ply report.json W H
With several ranks the mesh is redistributed (RedistributeDataSet) so that every rank renders a
part and IceT composites the depth buffers: the usual sort-last batch setup.
"""
import json
import sys
import time

from paraview import servermanager
from paraview.simple import (ColorBy, CreateView, PLYReader, RedistributeDataSet, Render,
                             SetActiveView, Show)

mesh, report, width, height = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
with open(report) as f:
    cameras = [frame["camera"] for frame in json.load(f)["frames"]]

ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
source = PLYReader(FileNames=[mesh])
if ranks > 1:
    source = RedistributeDataSet(Input=source)
view = CreateView("RenderView")
SetActiveView(view)
view.ViewSize = [width, height]
view.OrientationAxesVisibility = 0
view.Background = [0.0, 0.0, 0.0]
display = Show(source, view)
display.SetRepresentationType("Surface")
ColorBy(display, ("CELLS", "RGB"))
display.MapScalars = 0  # the faces' own colours

times = []
for cam in cameras:
    view.CameraPosition = cam["position"]
    view.CameraFocalPoint = cam["look_at"]
    view.CameraViewUp = cam["up"]
    view.CameraViewAngle = cam["fov"]
    view.GetActiveCamera().SetClippingRange(cam["near"], cam["far"])
    start = time.perf_counter()
    Render(view)
    times.append(time.perf_counter() - start)

if servermanager.vtkProcessModule.GetProcessModule().GetPartitionId() == 0:
    print(json.dumps({"ranks": ranks, "frame_seconds": times}))
