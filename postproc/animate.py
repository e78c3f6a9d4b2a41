"""`python -m postproc animate RUN.h5`: the launch as a movie drawn with matplotlib (Agg).

Two views of the same geometry as the ParaView scene (postproc.launch_geometry), in the
paper's frame oxy1z1 (x forward, y1 = -y to port, z1 = -z up; layout.to_plot_frame): the
end view seen from ahead (y1-z1: ship section and side plane, boat section, falls) and the
side view seen from starboard (x-z1), both with the sea surface through the boat and the
falls coloured by tension; under them strip charts of the tensions and the boat's CG
acceleration with a moving cursor and the launch's events (impacts, waterborne, release).
MP4 through imageio-ffmpeg's own ffmpeg binary (H.264, yuv420p); a .gif name, or no ffmpeg,
gives an animated GIF through Pillow (matplotlib's dependency). `still` draws one frame.
"""
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402
from matplotlib.patches import Polygon  # noqa: E402

from . import launch_geometry as geo  # noqa: E402
from . import layout  # noqa: E402

SIZE = (1024, 720)       # pixels: multiples of 16, as H.264 in yuv420p wants
DPI = 100
MAX_FRAMES = 400         # default --every: about this many frames for the whole run
SEA_SAMPLES = 121        # points along each view's sea line
VIEW_MARGIN = 4.0        # m around what moves
VIEW_SHAPE = 1.15        # width/height of a view's window (fills its axes)


class Drawing:
    """The figure and its artists; draw(i) moves them to frame i (an index into frames)."""

    def __init__(self, run, frames):
        self.run, self.frames = run, frames
        self.t = run.time[frames]
        self._geometry()
        self.fig = plt.figure(figsize=(SIZE[0] / DPI, SIZE[1] / DPI), dpi=DPI)
        grid = self.fig.add_gridspec(3, 2, height_ratios=[3.2, 1, 1], hspace=0.45,
                                     left=0.07, right=0.97, top=0.93, bottom=0.07)
        self.end = self.fig.add_subplot(grid[0, 0])
        self.side = self.fig.add_subplot(grid[0, 1])
        self.tension_ax = self.fig.add_subplot(grid[1, :])
        self.accel_ax = self.fig.add_subplot(grid[2, :], sharex=self.tension_ax)
        self.title = self.fig.suptitle("")
        self._views()
        self._strips()
        self._freeze()

    def _geometry(self):
        """Everything drawn, in the plot frame, over the frames."""
        run, frames = self.run, self.frames
        ship = geo.ship_pose(run, frames)
        box, side = geo.ship_box(run), geo.side_plane(run)
        mid = 0.5 * (box[:, 0].min() + box[:, 0].max())
        keel, top, half_b = box[:, 2].max(), box[:, 2].min(), box[:, 1].max()
        section = [[mid, -half_b, keel], [mid, half_b, keel], [mid, half_b, top],
                   [mid, -half_b, top]]
        profile = [[box[:, 0].min(), side[0, 1], keel], [box[:, 0].max(), side[0, 1], keel],
                   [box[:, 0].max(), side[0, 1], top], [box[:, 0].min(), side[0, 1], top]]
        self.ship_section = layout.to_plot_frame(ship.apply(section))
        self.ship_profile = layout.to_plot_frame(ship.apply(profile))
        self.side_line = layout.to_plot_frame(ship.apply([[mid, side[0, 1], side[0, 2]],
                                                          [mid, side[0, 1], side[2, 2]]]))
        hull = geo.boat_hull(run).reshape(geo.BOAT_STATIONS, 4, 3)
        boat = geo.boat_pose(run, frames)
        self.boat_section = layout.to_plot_frame(boat.apply(hull[geo.BOAT_STATIONS // 2]))
        keel_line = np.c_[hull[:, 0, 0], np.zeros(len(hull)), hull[:, 0, 2]]
        top_line = np.c_[hull[:, 0, 0], np.zeros(len(hull)), hull[:, 2, 2]]
        self.boat_profile = layout.to_plot_frame(boat.apply(np.vstack([keel_line,
                                                                       top_line[::-1]])))
        self.boat_cg = layout.to_plot_frame(boat.r)
        self.falls = geo.falls(run, frames)
        self.fall_points = layout.to_plot_frame(self.falls.points)
        self.fenders = layout.to_plot_frame(geo.fenders(run, frames))
        force = run.get(layout.CONTACT_FORCE)
        self.fender_force = force[frames] if force is not None else \
            np.zeros(self.fenders.shape[:2])

    def _limits(self, axis):
        """A fixed window (along plot-frame axis 0, 1 or 2) over the boat, falls and
        fenders of every frame, with a margin."""
        values = np.concatenate([self.boat_profile[..., axis].ravel(),
                                 self.boat_section[..., axis].ravel(),
                                 self.fall_points[..., axis].ravel(),
                                 self.fenders[..., axis].ravel()])
        return values.min() - VIEW_MARGIN, values.max() + VIEW_MARGIN

    def _window(self, h, lo_z, hi_z):
        """The view's horizontal window: what moves, widened to the axes' shape."""
        lo, hi = self._limits(h)
        half = 0.5 * max(hi - lo, VIEW_SHAPE * (hi_z - lo_z))
        return 0.5 * (lo + hi) - half, 0.5 * (lo + hi) + half

    def _views(self):
        """The end and side views' artists and fixed windows (equal aspect)."""
        lo_z, hi_z = self._limits(2)
        lo_z = min(lo_z, -VIEW_MARGIN)
        cmap, top = plt.get_cmap("plasma"), run_peak_tension(self.run)
        self.norm = matplotlib.colors.Normalize(0.0, top / 1e3)
        self.views = {}
        for ax, (h, name) in ((self.end, (1, "end view from ahead: y1 = -y [m] (port +)")),
                              (self.side, (0, "side view from starboard: x [m] (forward +)"))):
            lo, hi = self._window(h, lo_z, hi_z)
            ax.set(xlim=(lo, hi), ylim=(lo_z, hi_z), xlabel=name, aspect="equal")
            ax.set_ylabel("z1 = -z [m] (up)")
            ax.set_facecolor("#eef4fa")
            view = dict(
                sea=ax.add_patch(Polygon(np.zeros((3, 2)), fc="#9cc3e6", ec="#1f5f9f",
                                         lw=1.2, alpha=0.85, zorder=3)),
                ship=ax.add_patch(Polygon(np.zeros((4, 2)), color="#8c8c96", alpha=0.8,
                                          lw=0, zorder=2)),
                side=ax.plot([], [], color="#333", lw=2.0, zorder=3)[0],
                boat=ax.add_patch(Polygon(np.zeros((4, 2)), fc="#ff7f0e", ec="#7a3d00",
                                          lw=1.0, zorder=4)),
                lines=ax.add_collection(LineCollection([], cmap=cmap, norm=self.norm,
                                                       lw=1.6, zorder=5)),
                nodes=ax.scatter([], [], s=10, color="k", zorder=6),
                fenders=ax.add_collection(LineCollection([], colors="k", lw=4, zorder=7)))
            view["sea_x"], view["bottom"] = np.linspace(lo, hi, SEA_SAMPLES), lo_z
            self.views[h] = view
            if not geo.has_sea(self.run):
                ax.text(0.02, 0.97, "sea: still water level (the run file records no waves)",
                        transform=ax.transAxes, fontsize=7, color="#1f3f5f", va="top")
        bar = self.fig.colorbar(self.views[0]["lines"], ax=[self.end, self.side],
                                shrink=0.8, pad=0.01)
        bar.set_label("tension [kN]")

    def _strips(self):
        """Tension and acceleration over the whole run, events marked, a cursor each."""
        run, t = self.run, self.run.time
        seg = run.get(layout.RIGGING_SEGMENT_TENSION)
        if seg is not None:
            self.tension_ax.plot(t, seg.max(axis=1) / 1e3, lw=0.8, label="falls (max)")
        sling = run.get(layout.SLING_TENSION)
        for s, name in enumerate(("fore", "aft")):
            self.tension_ax.plot(t, sling[:, s] / 1e3, lw=0.8, label=f"sling {name}")
        a = run.get(layout.BOAT_ACCELERATION)
        self.accel_ax.plot(t, np.hypot(a[:, 0], a[:, 1]), lw=0.8, label="CG |a_xy|")
        self.accel_ax.plot(t, -a[:, 2], lw=0.8, label="CG a_z1 (up)")
        self.tension_ax.set_ylabel("tension [kN]")
        self.accel_ax.set(ylabel="a [m/s^2]", xlabel="t [s]", xlim=(t[0], t[-1]))
        self.cursors = []
        for ax in (self.tension_ax, self.accel_ax):
            self._events(ax)
            ax.grid(True, alpha=0.3)
            ax.legend(fontsize=7, loc="upper left", ncol=6)
            self.cursors.append(ax.axvline(t[0], color="k", lw=1.2))

    def _events(self, ax):
        """Impacts (red dotted), waterborne (blue) and release (green) times."""
        impacts = self.run.get(layout.IMPACT_TIME)
        for k, when in enumerate([] if impacts is None else np.ravel(impacts)):
            ax.axvline(when, color="r", ls=":", lw=1, label="impact" if k == 0 else None)
        for name, colour, label in ((layout.WATERBORNE_TIME, "tab:blue", "waterborne"),
                                    (layout.RELEASE_TIME, "tab:green", "release")):
            when = self.run.event(name)
            if when is not None:
                ax.axvline(when, color=colour, ls="--", lw=1, label=label)

    def draw(self, i):
        """Move every artist to frame i and render; returns the RGB pixels."""
        t = self.t[i]
        self.title.set_text(f"{os.path.basename(self.run.path)}   t = {t:6.2f} s")
        for h, view in self.views.items():
            ship = self.ship_section[i] if h == 1 else self.ship_profile[i]
            boat = self.boat_section[i] if h == 1 else self.boat_profile[i]
            view["ship"].set_xy(ship[:, [h, 2]])
            view["boat"].set_xy(boat[:, [h, 2]])
            view["side"].set_data(self.side_line[i][:, h], self.side_line[i][:, 2])
            self._draw_falls(view, h, i)
            eta = self._sea(view["sea_x"], h, i)
            view["sea"].set_xy(np.vstack([np.c_[view["sea_x"], eta],
                                          [[view["sea_x"][-1], view["bottom"]],
                                           [view["sea_x"][0], view["bottom"]]]]))
        for cursor in self.cursors:
            cursor.set_xdata([t, t])
        canvas = self.fig.canvas
        canvas.restore_region(self.background)
        for artist in self.moving:
            self.fig.draw_artist(artist)
        return np.asarray(canvas.buffer_rgba())[..., :3].copy()

    def _freeze(self):
        """Blitting: render the axes, ticks and strip charts once; draw() then only
        redraws the moving artists over that background (a fifth of a full draw)."""
        self.moving = [self.title] + self.cursors + [
            a for view in self.views.values() for k, a in view.items()
            if k not in ("sea_x", "bottom")]
        self.moving.sort(key=lambda artist: artist.get_zorder())  # draw_artist keeps order
        for artist in self.moving:
            artist.set_animated(True)
        self.fig.canvas.draw()
        self.background = self.fig.canvas.copy_from_bbox(self.fig.bbox)

    def _draw_falls(self, view, h, i):
        p = self.fall_points[i][:, [h, 2]]
        view["lines"].set_segments(p[self.falls.segments])
        view["lines"].set_array(self.falls.tension[i] / 1e3)
        wheels = np.isin(self.falls.kind, (geo.SHEAVE, geo.BLOCK, geo.DRUM))
        view["nodes"].set_offsets(p[wheels])
        fenders = self.fenders[i][..., [h, 2]]
        view["fenders"].set_segments(fenders)
        view["fenders"].set_color(np.where(self.fender_force[i][:, None] > 0,
                                           [[0.85, 0.1, 0.1, 1]], [[0, 0, 0, 1]]))

    def _sea(self, along, h, i):
        """Surface elevation along the view's axis through the boat's CG."""
        cg = layout.to_plot_frame(self.run.get(layout.BOAT_POSITION)[self.frames[i]])
        x = along if h == 0 else np.full_like(along, cg[0])
        y1 = along if h == 1 else np.full_like(along, cg[1])
        return geo.sea_elevation(self.run, self.t[i], x, -y1)


def run_peak_tension(run):
    """The largest recorded fall or sling tension [N] (at least 1): the colour scale's top,
    the same for every frame."""
    values = [run.get(name) for name in (layout.RIGGING_SEGMENT_TENSION, layout.SLING_TENSION)]
    return max([1.0] + [float(np.max(v)) for v in values if v is not None and v.size])


def default_every(run):
    """About MAX_FRAMES frames for the whole run."""
    return max(1, math.ceil(len(run.time) / MAX_FRAMES))


def _load(path):
    run = layout.load(path)
    run.require([layout.BOAT_POSITION, layout.BOAT_EULER, layout.SLING_TENSION,
                 layout.BOAT_ACCELERATION], "boat on its falls (a 'launch' or boat run)")
    return run


# What `out` may name as a file: a movie, or a still in any image format Pillow writes.
MOVIE_SUFFIXES = (".mp4", ".gif")
STILL_SUFFIXES = (".png", ".jpg", ".jpeg", ".webp", ".tif", ".tiff", ".bmp", ".gif")


def _target(path, out, suffix, kinds=MOVIE_SUFFIXES + (".png",)):
    """`out` itself when it names a file of one of `kinds`, else <out>/<run stem><suffix>
    (a folder)."""
    if os.path.splitext(out)[1].lower() in kinds:
        folder = os.path.dirname(out)
        target = out
    else:
        folder = out
        target = os.path.join(out, os.path.splitext(os.path.basename(path))[0] + suffix)
    if folder:
        os.makedirs(folder, exist_ok=True)
    return target


def still(path, out, when):
    """One frame, at the sample nearest time `when`, as a PNG; returns its path."""
    run = _load(path)
    index = int(np.argmin(np.abs(run.time - when)))
    drawing = Drawing(run, np.array([index]))
    target = _target(path, out, "_frame.png", STILL_SUFFIXES)
    from PIL import Image
    image = Image.fromarray(drawing.draw(0))
    # JPEG and BMP hold no alpha channel
    image.convert("RGB").save(target, optimize=True)
    plt.close(drawing.fig)
    return target


def movie(path, out, fps=20.0, every=None):
    """The animation as MP4 (or GIF where asked or where ffmpeg fails); returns (path,
    frame count)."""
    run = _load(path)
    frames = geo.frame_indices(run, every or default_every(run))
    drawing = Drawing(run, frames)
    target = _target(path, out, ".mp4")
    try:
        if target.lower().endswith(".mp4"):
            try:
                _write_mp4(target, drawing, fps)
                return target, len(frames)
            except (ImportError, OSError, RuntimeError) as exc:
                print(f"postproc: no MP4 ({exc}); writing a GIF instead", file=sys.stderr)
                target = target[:-4] + ".gif"
        _write_gif(target, drawing, fps)
        return target, len(frames)
    finally:
        plt.close(drawing.fig)


def _write_mp4(target, drawing, fps):
    """H.264 through imageio-ffmpeg's ffmpeg, frames piped as raw RGB."""
    import imageio_ffmpeg
    writer = imageio_ffmpeg.write_frames(target, SIZE, fps=fps, codec="libx264",
                                         pix_fmt_out="yuv420p", quality=7,
                                         macro_block_size=16)
    writer.send(None)
    try:
        for i in range(len(drawing.frames)):
            writer.send(drawing.draw(i).tobytes())
    finally:
        writer.close()


def _write_gif(target, drawing, fps):
    """An animated GIF through Pillow (adaptive palette per frame, looping)."""
    from PIL import Image
    images = [Image.fromarray(drawing.draw(i)).convert("P", palette=Image.Palette.ADAPTIVE)
              for i in range(len(drawing.frames))]
    images[0].save(target, save_all=True, append_images=images[1:], loop=0,
                   duration=max(20, round(1000.0 / fps)), optimize=False)
