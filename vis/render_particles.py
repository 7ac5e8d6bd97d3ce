#!/usr/bin/python3
r"""Render sphark particle frames (.vtp, or frames of a .pvd series: .vtp or .pvtp) to PNG.

VTK renders the points offscreen (vtkRenderWindow, SetOffScreenRendering(1), parallel
projection onto a known world rectangle); matplotlib frames that image with true x/y axes, a
colour bar and a title with the time. Points are coloured by a named point array (vectors by
magnitude, or --component). 2D scenes (all z = 0) are viewed from +z; 1D frames (y = z = 0)
are plotted as the value against x; 3D frames get an oblique view without axes. VTK needs a
display:
run under `xvfb-run -a /usr/bin/python3 ...` when $DISPLAY is unset.

One picture:
  render_particles.py out/drop.pvd --array density --out density.png [--frame -1]
Colour range: per array over its panels, from the --clip and 100 - --clip percentiles of the
values (default 0.5: a few spikes do not wash out the field; the bar's arrows show the clipped
ends; --clip 0: the full data range), unless --range. Large or small scales go into the bar's
label (x 1ek) rather than an offset that would overlap the title.
Panel of frames x arrays:
  render_particles.py out/drop.pvd --grid 2x2 --frames 0 1 2 -1 --array pressure --out g.png
  render_particles.py out/drop.pvd --grid 1x2 --frame -1 --arrays density velocity --out g.png
"""
import argparse
import math
import os
import sys
import xml.etree.ElementTree as ET
from atomic_save import save_figure  # noqa: E402


def fail(msg):
    print(f"render_particles.py: {msg}", file=sys.stderr)
    sys.exit(2)


def series_frames(path):
    """[(time or None, frame path)] for a .pvd, or [(None, path)] for a .vtp or .pvtp."""
    if not os.path.isfile(path):
        fail(f"input: no file '{path}'")
    if path.endswith(".vtp") or path.endswith(".pvtp"):
        return [(None, path)]
    if not path.endswith(".pvd"):
        fail(f"input: '{path}' is neither .vtp nor .pvd")
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as e:
        fail(f"input: '{path}' is not valid XML: {e}")
    base = os.path.dirname(path)
    frames = [(float(ds.get("timestep", "nan")), os.path.join(base, ds.get("file", "")))
              for ds in root.iter("DataSet")]
    if not frames:
        fail(f"input: '{path}' lists no frames")
    return frames


def pick(frames, index):
    if not -len(frames) <= index < len(frames):
        fail(f"--frame: {index} out of range (the series has {len(frames)} frames)")
    return frames[index]


def load(vtk, time, path):
    # a distributed run's frames are .pvtp (one piece per rank, merged by the parallel reader)
    reader = vtk.vtkXMLPPolyDataReader() if path.endswith(".pvtp") else vtk.vtkXMLPolyDataReader()
    if not os.path.isfile(path) or not reader.CanReadFile(path):
        fail(f"input: cannot read '{path}'")
    reader.SetFileName(path)
    reader.Update()
    poly = reader.GetOutput()
    if time is None:
        tv = poly.GetFieldData().GetArray("TimeValue")
        time = tv.GetComponent(0, 0) if tv is not None else None
    return poly, time


def point_array(poly, name, component, path):
    """(vtk array, component index, or -1 for the magnitude)."""
    pd = poly.GetPointData()
    arr = pd.GetArray(name)
    if arr is None:
        names = [pd.GetArrayName(i) for i in range(pd.GetNumberOfArrays())]
        fail(f"--array: no point array '{name}' in '{path}' (has: {', '.join(names)})")
    if arr.GetNumberOfComponents() == 1:
        return arr, 0
    comp = {"x": 0, "y": 1, "z": 2, "mag": -1}[component]
    if comp >= arr.GetNumberOfComponents():
        fail(f"--component: '{name}' has only {arr.GetNumberOfComponents()} components")
    return arr, comp


def label(name, arr, component):
    if arr.GetNumberOfComponents() == 1:
        return name
    return f"|{name}|" if component == "mag" else f"{name}_{component}"


def median_spacing(vtk, poly):
    """Median nearest-neighbour distance over up to 400 sample points."""
    n = poly.GetNumberOfPoints()
    if n < 2:
        return None
    loc = vtk.vtkStaticPointLocator()
    loc.SetDataSet(poly)
    loc.BuildLocator()
    ids = vtk.vtkIdList()
    d = []
    for i in range(0, n, max(1, n // 400)):
        p = poly.GetPoint(i)
        loc.FindClosestNPoints(2, p, ids)
        q = poly.GetPoint(ids.GetId(1) if ids.GetId(0) == i else ids.GetId(0))
        d.append(math.dist(p, q))
    d.sort()
    return d[len(d) // 2] or None


ZOOM_3D = 1.3


def point_size_3d(bounds, spacing, height_px, view_angle_deg=30.0):
    """Pixels per particle spacing at the focal plane after ResetCamera + Zoom(ZOOM_3D): the
    camera sits at r / sin(a/2) from the centre of the bounding sphere of radius r, so the
    focal plane shows a height of 2 r / cos(a/2) / ZOOM_3D."""
    r = 0.5 * math.dist(bounds[0::2], bounds[1::2])
    half = math.radians(view_angle_deg) / 2
    return spacing * height_px * ZOOM_3D * math.cos(half) / (2 * r) if r > 0 else 4.0


def clipped_range(values, percent):
    """(lo, hi): the percent and 100 - percent percentiles of the finite values (0: min, max)."""
    import numpy as np
    v = values[np.isfinite(values)]
    if v.size == 0:
        return 0.0, 0.0
    if percent <= 0:
        return float(v.min()), float(v.max())
    lo, hi = np.percentile(v, [percent, 100 - percent])
    return float(lo), float(hi)


def scale_bar_ticks(bar, lo, hi):
    """Tick labels in units of 10^k, with k in the bar's label beside it (no offset text)."""
    import matplotlib.ticker as ticker
    big = max(abs(lo), abs(hi))
    if not big > 0 or 1e-2 <= big < 1e4:
        bar.formatter = ticker.ScalarFormatter(useOffset=False)
        bar.update_ticks()
        return
    k = math.floor(math.log10(big))
    bar.formatter = ticker.FuncFormatter(lambda v, _pos: f"{v / 10.0 ** k:g}")
    bar.update_ticks()
    bar.set_label(f"× 1e{k}", fontsize=8)


def values_of(arr, comp):
    from vtkmodules.util.numpy_support import vtk_to_numpy
    import numpy as np
    v = vtk_to_numpy(arr)
    if v.ndim == 1:
        return v
    return np.linalg.norm(v, axis=1) if comp == -1 else v[:, comp]


def render_points(vtk, poly, name, comp, lo, hi, cmap, rect, px, point_size, flat):
    """RGB image (numpy, rows top to bottom) of the points; rect = (x0, x1, y0, y1) world."""
    from vtkmodules.util.numpy_support import vtk_to_numpy

    lut = vtk.vtkLookupTable()
    lut.SetNumberOfTableValues(256)
    for i in range(256):
        r, g, b, _ = cmap(i / 255.0)
        lut.SetTableValue(i, r, g, b, 1.0)
    lut.SetTableRange(lo, hi)
    if comp == -1:
        lut.SetVectorModeToMagnitude()
    else:
        lut.SetVectorModeToComponent()
        lut.SetVectorComponent(comp)
    lut.Build()

    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputData(poly)
    mapper.SetScalarModeToUsePointFieldData()
    mapper.SelectColorArray(name)
    mapper.SetLookupTable(lut)
    mapper.SetUseLookupTableScalarRange(True)
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetPointSize(point_size)
    actor.GetProperty().SetRenderPointsAsSpheres(True)
    if flat:  # a 2D field: flat discs in their true colour, not shaded balls with dark rims
        actor.GetProperty().LightingOff()

    ren = vtk.vtkRenderer()
    ren.SetBackground(1, 1, 1)
    ren.AddActor(actor)
    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(*px)
    window.SetMultiSamples(0)
    window.AddRenderer(ren)
    cam = ren.GetActiveCamera()
    if flat:  # view from +z, parallel: the window shows exactly `rect`
        cx, cy = 0.5 * (rect[0] + rect[1]), 0.5 * (rect[2] + rect[3])
        cam.ParallelProjectionOn()
        cam.SetFocalPoint(cx, cy, 0)
        cam.SetPosition(cx, cy, 1)
        cam.SetViewUp(0, 1, 0)
        cam.SetParallelScale(0.5 * (rect[3] - rect[2]))
        cam.SetClippingRange(0.5, 1.5)
    else:  # oblique perspective view, z up, of the bounding sphere (see point_size_3d)
        ren.ResetCamera()
        fx, fy, fz = cam.GetFocalPoint()
        d = cam.GetDistance()
        az, el = math.radians(-60), math.radians(25)
        cam.SetPosition(fx + d * math.cos(el) * math.cos(az), fy + d * math.cos(el) * math.sin(az),
                        fz + d * math.sin(el))
        cam.SetViewUp(0, 0, 1)
        cam.Zoom(ZOOM_3D)
        ren.ResetCameraClippingRange()
        # x/y/z triad in the lower-left corner, seen from the same direction.
        triad = vtk.vtkRenderer()
        triad.SetViewport(0, 0, 0.2, 0.2)
        triad.SetBackground(1, 1, 1)
        axes = vtk.vtkAxesActor()
        for cap in (axes.GetXAxisCaptionActor2D(), axes.GetYAxisCaptionActor2D(),
                    axes.GetZAxisCaptionActor2D()):
            cap.GetCaptionTextProperty().SetColor(0, 0, 0)
            cap.GetCaptionTextProperty().ShadowOff()
        triad.AddActor(axes)
        tc = triad.GetActiveCamera()
        tc.SetFocalPoint(0, 0, 0)
        tc.SetPosition(4 * math.cos(el) * math.cos(az), 4 * math.cos(el) * math.sin(az),
                       4 * math.sin(el))
        tc.SetViewUp(0, 0, 1)
        triad.ResetCameraClippingRange()
        window.AddRenderer(triad)
    window.Render()
    grab = vtk.vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.ReadFrontBufferOff()
    grab.Update()
    img = grab.GetOutput()
    w, h, _ = img.GetDimensions()
    rgb = vtk_to_numpy(img.GetPointData().GetScalars()).reshape(h, w, -1)[::-1, :, :3]
    window.Finalize()
    return rgb.copy()


def main(argv=None):
    ap = argparse.ArgumentParser(description="Render particle frames to PNG (VTK offscreen).",
                                 formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog=__doc__)
    ap.add_argument("input", help=".vtp file or .pvd series")
    ap.add_argument("--array", help="point array to colour by (e.g. density)")
    ap.add_argument("--arrays", nargs="+", help="several arrays (grid mode)")
    ap.add_argument("--component", choices=["mag", "x", "y", "z"], default="mag",
                    help="for vector arrays: magnitude (default) or one component")
    ap.add_argument("--frame", type=int, default=-1, help="frame of a .pvd (default -1 = last)")
    ap.add_argument("--frames", nargs="+", type=int, help="several frames (grid mode)")
    ap.add_argument("--grid", metavar="RxC", help="panel layout, e.g. 2x2")
    ap.add_argument("--range", nargs=2, type=float, metavar=("LO", "HI"),
                    help="colour range (default: see --clip, per array over its panels)")
    ap.add_argument("--clip", type=float, default=0.5, metavar="P",
                    help="colour range from the P and 100-P percentiles (default 0.5; 0: min..max)")
    ap.add_argument("--size", nargs=2, type=int, metavar=("W", "H"),
                    help="PNG size in pixels (default 900 900; grid: 600 x 540 per panel)")
    ap.add_argument("--point-size", type=float,
                    help="point diameter in pixels (default: the particle spacing)")
    ap.add_argument("--cmap", default="viridis", help="matplotlib colour map (default viridis)")
    ap.add_argument("--title", help="title line above the panels")
    ap.add_argument("--out", required=True, help="output PNG")
    args = ap.parse_args(argv)

    frames = series_frames(args.input)
    arrays = args.arrays or ([args.array] if args.array else None)
    if not arrays:
        fail("--array: required (the point array to colour by)")
    if args.grid:
        try:
            rows, cols = (int(v) for v in args.grid.lower().split("x"))
            if rows < 1 or cols < 1:
                raise ValueError
        except ValueError:
            fail(f"--grid: bad value '{args.grid}' (expected ROWSxCOLS, e.g. 2x2)")
        panels = [(f, a) for f in (args.frames or [args.frame]) for a in arrays]
        if len(panels) > rows * cols:
            fail(f"--grid: {len(panels)} panels do not fit in {args.grid}")
    else:
        if len(arrays) != 1 or args.frames:
            fail("--arrays/--frames: several panels need --grid RxC")
        rows = cols = 1
        panels = [(args.frame, arrays[0])]
    size = args.size or ([900, 900] if len(panels) == 1 else [600 * cols, 540 * rows])
    auto_size = args.size is None and len(panels) == 1
    if min(size) < 50:
        fail(f"--size: {size[0]} x {size[1]} is too small")
    if not 0 <= args.clip < 50:
        fail(f"--clip: need 0 <= P < 50 (got {args.clip:g})")
    if args.range and not args.range[0] < args.range[1]:
        fail(f"--range: need LO < HI (got {args.range[0]:g} {args.range[1]:g})")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    try:
        cmap = matplotlib.colormaps[args.cmap]
    except KeyError:
        fail(f"--cmap: unknown colour map '{args.cmap}'")
    import vtk

    loaded = {}
    for f, _ in panels:
        if f not in loaded:
            t, path = pick(frames, f)
            loaded[f] = load(vtk, t, path) + (path,)
    ranges = {}  # per array: --range, else the union of the clipped ranges of its panels
    extent = {}  # per array: the full data range over its panels
    for f, a in panels:
        arr, comp = point_array(loaded[f][0], a, args.component, loaded[f][2])
        lo, hi = args.range or clipped_range(values_of(arr, comp), args.clip)
        full = arr.GetRange(comp)
        if a in ranges:
            lo, hi = min(lo, ranges[a][0]), max(hi, ranges[a][1])
            full = (min(full[0], extent[a][0]), max(full[1], extent[a][1]))
        ranges[a], extent[a] = (lo, hi), full

    if auto_size:  # one flat panel: fit the PNG height to the data's aspect ratio
        b = loaded[panels[0][0]][0].GetBounds()
        if b[4] == b[5] == 0.0 and b[1] > b[0]:
            aspect = (b[3] - b[2]) / (b[1] - b[0])
            size = [900, int(min(max(0.78 * 900 * aspect + 200, 400), 1100))]
    dpi = 150
    fig, axes = plt.subplots(rows, cols, figsize=(size[0] / dpi, size[1] / dpi), dpi=dpi,
                             squeeze=False)
    for k, ax in enumerate(axes.flat):
        if k >= len(panels):
            ax.set_axis_off()
            continue
        f, a = panels[k]
        poly, time, path = loaded[f]
        arr, comp = point_array(poly, a, args.component, path)
        lo, hi = ranges[a]
        if hi <= lo:  # constant field: give the colour bar a scale
            pad = abs(lo) * 1e-6 or 1e-12
            lo, hi = lo - pad, hi + pad
        b = poly.GetBounds()
        flat = b[4] == 0.0 and b[5] == 0.0
        # Axes box in pixels (about 70 % x 80 % of the panel) sets the render resolution.
        box_w, box_h = 0.68 * size[0] / cols, 0.72 * size[1] / rows
        spacing = median_spacing(vtk, poly) or 0.02 * max(b[1] - b[0], b[3] - b[2], 1.0)
        if flat and b[2] == b[3] == 0.0:  # 1D: the value against x, no picture needed
            from vtkmodules.util.numpy_support import vtk_to_numpy
            x = vtk_to_numpy(poly.GetPoints().GetData())[:, 0]
            order = x.argsort()
            ax.plot(x[order], values_of(arr, comp)[order], ".-", markersize=3, linewidth=0.6)
            ax.set_xlabel("x")
            ax.set_ylabel(label(a, arr, args.component))
            ax.set_ylim(lo - 0.05 * (hi - lo), hi + 0.05 * (hi - lo))
            ax.grid(True, alpha=0.35)
            when = f"   t = {time:.6g}" if time is not None and math.isfinite(time) else ""
            ax.set_title(label(a, arr, args.component) + when, fontsize=10)
            ax.tick_params(labelsize=8)
            continue
        if flat:
            margin = 0.6 * spacing + 0.02 * max(b[1] - b[0], b[3] - b[2])
            x0, x1, y0, y1 = b[0] - margin, b[1] + margin, b[2] - margin, b[3] + margin
            scale = 2 * min(box_w / (x1 - x0), box_h / (y1 - y0))  # render pixels per unit
            px = (max(int((x1 - x0) * scale), 16), max(int((y1 - y0) * scale), 16))
            x1 = x0 + px[0] / scale  # exact world rectangle of the pixel grid
            y1 = y0 + px[1] / scale
            # 2 median spacings: the squares overlap enough to close the gaps of a disordered set
            # and of regions at half the median density
            ps = args.point_size * 2 if args.point_size else max(2.0 * spacing * scale, 2.0)
            img = render_points(vtk, poly, a, comp, lo, hi, cmap, (x0, x1, y0, y1), px, ps, True)
            ax.imshow(img, extent=(x0, x1, y0, y1), origin="upper", interpolation="antialiased")
            ax.set_xlabel("x")
            ax.set_ylabel("y")
            ax.set_aspect("equal")
        else:
            px = (int(2 * box_w), int(2 * box_h))
            ps = args.point_size * 2 if args.point_size else \
                max(point_size_3d(b, spacing, px[1]), 2.0)
            img = render_points(vtk, poly, a, comp, lo, hi, cmap, None, px, ps, False)
            ax.imshow(img)
            ax.set_axis_off()
        mappable = matplotlib.cm.ScalarMappable(matplotlib.colors.Normalize(lo, hi), cmap)
        from mpl_toolkits.axes_grid1 import make_axes_locatable
        cax = make_axes_locatable(ax).append_axes("right", size="4%", pad=0.08)
        extend = {(False, False): "neither", (True, False): "min", (False, True): "max",
                  (True, True): "both"}[(extent[a][0] < lo, extent[a][1] > hi)]
        bar = fig.colorbar(mappable, cax=cax, extend=extend)
        scale_bar_ticks(bar, lo, hi)
        cax.tick_params(labelsize=8)
        when = f"   t = {time:.6g}" if time is not None and math.isfinite(time) else ""
        ax.set_title(label(a, arr, args.component) + when, fontsize=10)
        ax.tick_params(labelsize=8)
    if args.title:
        fig.suptitle(args.title, fontsize=11)
    fig.tight_layout()
    try:
        save_figure(fig, args.out, dpi=dpi, bbox_inches="tight", pad_inches=0.08)
    except OSError as e:
        fail(f"--out: cannot write '{args.out}': {e.strerror}")
    print(args.out)


if __name__ == "__main__":
    main()
