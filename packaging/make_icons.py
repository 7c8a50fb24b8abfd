"""Render the application icon (resources/icons/zwidth.svg) to PNG, ICO and ICNS.

Usage::

    python packaging/make_icons.py            # writes resources/icons/zwidth-<N>.png, zwidth.ico, zwidth.icns
    python packaging/make_icons.py --check    # exit 1 if a committed PNG is missing or stale
    python packaging/make_icons.py --iconset zwidth.iconset   # macOS: input of `iconutil -c icns`

Rendering uses Qt only (``QSvgRenderer`` from PySide6.QtSvg, which PySide6-Essentials ships), so the
PNGs are the same on every platform.  The Windows ``.ico`` and the macOS ``.icns`` are assembled
from those PNGs with Pillow when it is installed (every size in one file); without Pillow the ``.ico``
falls back to Qt's ``ico`` image plugin (a single 256 px image) and the ``.icns`` to Qt's ``icns``
plugin.  On macOS the canonical way is ``iconutil`` (see packaging/README.md).
"""

from __future__ import annotations

import argparse
import io
import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
ICON_DIR = ROOT / "resources" / "icons"
SOURCE = ICON_DIR / "zwidth.svg"
PNG_SIZES = (16, 32, 48, 64, 128, 256, 512)
ICO_SIZES = (16, 24, 32, 48, 64, 128, 256)
ICNS_SIZES = (16, 32, 64, 128, 256, 512, 1024)

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
sys.path.insert(0, str(ROOT))

from app import qt_compat  # noqa: E402,F401 - before any Qt call (PySide6 6.12 on Python 3.11)
from PySide6.QtCore import QBuffer, QByteArray, QIODevice, Qt  # noqa: E402
from PySide6.QtGui import QGuiApplication, QImage, QImageWriter, QPainter  # noqa: E402
from PySide6.QtSvg import QSvgRenderer  # noqa: E402


def png_path(size: int) -> Path:
    return ICON_DIR / f"zwidth-{size}.png"


def render(size: int, source: Path = SOURCE) -> QImage:
    """The SVG rendered to a ``size`` x ``size`` transparent ARGB image."""
    renderer = QSvgRenderer(str(source))
    if not renderer.isValid():
        raise SystemExit(f"make_icons: cannot parse {source}")
    image = QImage(size, size, QImage.Format.Format_ARGB32_Premultiplied)
    image.fill(Qt.GlobalColor.transparent)
    painter = QPainter(image)
    painter.setRenderHint(QPainter.RenderHint.Antialiasing)
    painter.setRenderHint(QPainter.RenderHint.SmoothPixmapTransform)
    renderer.render(painter)
    painter.end()
    return image.convertToFormat(QImage.Format.Format_ARGB32)


def png_bytes(image: QImage) -> bytes:
    data = QByteArray()
    buffer = QBuffer(data)
    buffer.open(QIODevice.OpenModeFlag.WriteOnly)
    image.save(buffer, "PNG")
    buffer.close()
    return bytes(data.data())


def _pillow():
    try:
        from PIL import Image
    except ImportError:
        return None
    return Image


def write_ico(images: dict[int, QImage], path: Path) -> str:
    Image = _pillow()
    if Image is not None:
        frames = [Image.open(io.BytesIO(png_bytes(images[s]))).convert("RGBA") for s in ICO_SIZES]
        frames[-1].save(path, format="ICO", sizes=[(s, s) for s in ICO_SIZES], append_images=frames[:-1])
        return f"Pillow, {len(ICO_SIZES)} sizes"
    if b"ico" in [bytes(f.data()) for f in QImageWriter.supportedImageFormats()]:
        if images[256].save(str(path), "ICO"):
            return "Qt ico plugin, 256 px only"
    return "skipped (neither Pillow nor Qt's ico plugin)"


def write_icns(images: dict[int, QImage], path: Path) -> str:
    Image = _pillow()
    if Image is not None:
        frames = [Image.open(io.BytesIO(png_bytes(images[s]))).convert("RGBA") for s in ICNS_SIZES]
        frames[-1].save(path, format="ICNS", append_images=frames[:-1])
        return f"Pillow, {len(ICNS_SIZES)} sizes"
    if b"icns" in [bytes(f.data()) for f in QImageWriter.supportedImageFormats()]:
        if images[1024].save(str(path), "ICNS"):
            return "Qt icns plugin, 1024 px only"
    return "skipped (neither Pillow nor Qt's icns plugin); use iconutil on macOS"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--check", action="store_true",
                        help="only check that the committed PNGs match the SVG (exit 1 if not)")
    parser.add_argument("--iconset", type=Path, metavar="DIR",
                        help="only write a macOS .iconset folder (for iconutil -c icns DIR)")
    args = parser.parse_args(argv)
    app = QGuiApplication.instance() or QGuiApplication(sys.argv[:1])  # noqa: F841 - fonts, plugins
    sizes = sorted(set(PNG_SIZES) | set(ICO_SIZES) | set(ICNS_SIZES))
    images = {size: render(size) for size in sizes}
    if args.check:
        stale = [png_path(s).name for s in PNG_SIZES
                 if not png_path(s).exists() or QImage(str(png_path(s))).convertToFormat(
                     QImage.Format.Format_ARGB32) != images[s]]
        if stale:
            print("make_icons: stale or missing: " + ", ".join(stale) + " (run packaging/make_icons.py)")
            return 1
        print("make_icons: PNGs up to date")
        return 0
    if args.iconset:
        args.iconset.mkdir(parents=True, exist_ok=True)
        for size in (16, 32, 128, 256, 512):
            images[size].save(str(args.iconset / f"icon_{size}x{size}.png"), "PNG")
            images[2 * size].save(str(args.iconset / f"icon_{size}x{size}@2x.png"), "PNG")
        print(f"wrote {args.iconset}; now run: iconutil -c icns {args.iconset} -o resources/icons/zwidth.icns")
        return 0
    ICON_DIR.mkdir(parents=True, exist_ok=True)
    for size in PNG_SIZES:
        if not images[size].save(str(png_path(size)), "PNG"):
            raise SystemExit(f"make_icons: cannot write {png_path(size)}")
        print(f"wrote {png_path(size).relative_to(ROOT)}")
    how = write_ico(images, ICON_DIR / "zwidth.ico")
    print(f"wrote resources/icons/zwidth.ico ({how})")
    how = write_icns(images, ICON_DIR / "zwidth.icns")
    print(f"wrote resources/icons/zwidth.icns ({how})")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
