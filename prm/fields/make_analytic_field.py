#!/usr/bin/env python3
"""Writes an analytic flow field as a VTK unstructured grid (.vtu) for
Sluice's imported-field checks (prm/geometry/imported_field.prm,
'imported field/check'):

  uniform stream     u = U,                  p = rho g . x
  solid-body vortex  u = Omega e_z x x,      p = rho Omega^2 (x^2 + y^2) / 2 + rho g . x

on a box of nx x ny x nz hexahedra (or each hexahedron cut into six
tetrahedra), with the fields as point data (exact at the nodes) or cell data
(at the cell centres), in any of VTK's encodings: ascii, inline base64
('binary') or appended raw, optionally zlib-compressed as VTK and deal.II do.
Only the standard library is used.

The files beside this script were written by

  make_analytic_field.py uniform --cells 8 2 4 --lower 0 0 0 --upper 0.4 0.04 0.2 \
      --U 0.3 0 0 --gravity 0 0 -9.81 --output uniform_stream.vtu
  make_analytic_field.py vortex --cells 10 10 1 --lower -0.1 -0.1 -0.01 \
      --upper 0.1 0.1 0.01 --omega 2 --output vortex_coarse.vtu
  make_analytic_field.py vortex --cells 10 10 1 --lower -0.1 -0.1 -0.01 \
      --upper 0.1 0.1 0.01 --omega 2 --tets --encoding appended --output vortex_coarse_tets.vtu
  make_analytic_field.py vortex --cells 40 40 1 --lower -0.1 -0.1 -0.01 \
      --upper 0.1 0.1 0.01 --omega 2 --encoding binary --compress --output vortex_fine.vtu
  make_analytic_field.py vortex --cells 40 40 1 --lower -0.1 -0.1 -0.01 \
      --upper 0.1 0.1 0.01 --omega 2 --cell-data --encoding appended --compress --float32 \
      --output vortex_fine_cell_data.vtu
"""
import argparse
import base64
import struct
import zlib

HEX_CORNERS = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0),
               (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
# The six tetrahedra of a hexahedron around its diagonal 0-6 (VTK node numbers).
HEX_TETS = [(0, 1, 2, 6), (0, 2, 3, 6), (0, 3, 7, 6), (0, 7, 4, 6), (0, 4, 5, 6), (0, 5, 1, 6)]


def grid(cells, lower, upper, tets):
    nx, ny, nz = cells
    h = [(upper[d] - lower[d]) / cells[d] for d in range(3)]
    points = [(lower[0] + i * h[0], lower[1] + j * h[1], lower[2] + k * h[2])
              for k in range(nz + 1) for j in range(ny + 1) for i in range(nx + 1)]
    index = lambda i, j, k: i + (nx + 1) * (j + (ny + 1) * k)
    cells_out = []
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                hexa = [index(i + a, j + b, k + c) for a, b, c in HEX_CORNERS]
                if tets:
                    cells_out += [[hexa[n] for n in t] for t in HEX_TETS]
                else:
                    cells_out.append(hexa)
    return points, cells_out


def field(kind, x, U, omega, rho, g):
    hydrostatic = rho * sum(g[d] * x[d] for d in range(3))
    if kind == "uniform":
        return tuple(U), hydrostatic
    u = (-omega * x[1], omega * x[0], 0.0)
    return u, rho * omega ** 2 * (x[0] ** 2 + x[1] ** 2) / 2 + hydrostatic


class Writer:
    """DataArrays in one encoding; 'appended' collects the raw blocks."""

    def __init__(self, encoding, compress):
        self.encoding, self.compress, self.appended = encoding, compress, b""

    def block(self, raw):
        if not self.compress:
            return struct.pack("<I", len(raw)) + raw
        # vtkZLibDataCompressor: one block here (VTK splits at 32 KiB; so do we).
        size = 32768
        chunks = [raw[i:i + size] for i in range(0, len(raw), size)] or [b""]
        packed = [zlib.compress(c) for c in chunks]
        header = struct.pack("<%dI" % (3 + len(packed)), len(chunks), size,
                             len(chunks[-1]) if len(chunks[-1]) < size else 0,
                             *[len(p) for p in packed])
        return header + b"".join(packed)

    def array(self, name, vtk_type, fmt, values, components):
        attributes = 'type="%s" Name="%s" NumberOfComponents="%d"' % (vtk_type, name, components)
        if self.encoding == "ascii":
            text = " ".join(repr(v) if isinstance(v, float) else str(v) for v in values)
            return '<DataArray %s format="ascii">%s</DataArray>\n' % (attributes, text)
        raw = struct.pack("<%d%s" % (len(values), fmt), *values)
        if self.encoding == "binary":
            if self.compress:  # the header and the data are encoded apart, as VTK does
                blob = self.block(raw)
                n = 4 * (3 + struct.unpack("<I", blob[:4])[0])
                text = (base64.b64encode(blob[:n]) + base64.b64encode(blob[n:])).decode()
            else:
                text = base64.b64encode(self.block(raw)).decode()
            return '<DataArray %s format="binary">%s</DataArray>\n' % (attributes, text)
        offset = len(self.appended)
        self.appended += self.block(raw)
        return '<DataArray %s format="appended" offset="%d"/>\n' % (attributes, offset)


def write(path, points, cells, tets, kind, on_cells, args):
    w = Writer(args.encoding, args.compress)
    real, real_fmt = ("Float32", "f") if args.float32 else ("Float64", "d")
    where = cells if on_cells else None
    samples = []
    for c in (cells if on_cells else range(len(points))):
        x = [sum(points[n][d] for n in c) / len(c) for d in range(3)] if on_cells else points[c]
        samples.append(field(kind, x, args.U, args.omega, args.rho, args.gravity))
    velocity = [v for u, _ in samples for v in u]
    pressure = [p for _, p in samples]
    data = (w.array("velocity", real, real_fmt, velocity, 3) +
            w.array("pressure", real, real_fmt, pressure, 1))
    body = "<Points>\n" + w.array("Points", real, real_fmt, [v for p in points for v in p], 3)
    body += "</Points>\n<Cells>\n"
    offsets, connectivity, n = [], [], 0
    for c in cells:
        connectivity += c
        n += len(c)
        offsets.append(n)
    body += w.array("connectivity", "Int64", "q", connectivity, 1)
    body += w.array("offsets", "Int64", "q", offsets, 1)
    body += w.array("types", "UInt8", "B", [10 if tets else 12] * len(cells), 1)
    body += "</Cells>\n"
    section = "CellData" if on_cells else "PointData"
    header = '<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian"'
    if args.compress:
        header += ' compressor="vtkZLibDataCompressor"'
    with open(path, "wb") as out:
        out.write(('<?xml version="1.0"?>\n%s>\n<UnstructuredGrid>\n'
                   '<Piece NumberOfPoints="%d" NumberOfCells="%d">\n<%s>\n%s</%s>\n%s'
                   '</Piece>\n</UnstructuredGrid>\n' %
                   (header, len(points), len(cells), section, data, section, body)).encode())
        if w.appended:
            out.write(b'<AppendedData encoding="raw">\n_' + w.appended + b"\n</AppendedData>\n")
        out.write(b"</VTKFile>\n")


def main():
    a = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    a.add_argument("kind", choices=["uniform", "vortex"])
    a.add_argument("--cells", type=int, nargs=3, required=True)
    a.add_argument("--lower", type=float, nargs=3, required=True)
    a.add_argument("--upper", type=float, nargs=3, required=True)
    a.add_argument("--U", type=float, nargs=3, default=[0.0, 0.0, 0.0], help="[m/s]")
    a.add_argument("--omega", type=float, default=0.0, help="[rad/s]")
    a.add_argument("--rho", type=float, default=1000.0, help="[kg/m^3] for the pressure")
    a.add_argument("--gravity", type=float, nargs=3, default=[0.0, 0.0, 0.0], help="[m/s^2]")
    a.add_argument("--tets", action="store_true", help="six tetrahedra per hexahedron")
    a.add_argument("--cell-data", action="store_true", help="values at the cell centres")
    a.add_argument("--encoding", choices=["ascii", "binary", "appended"], default="ascii")
    a.add_argument("--compress", action="store_true", help="zlib, as VTK and deal.II")
    a.add_argument("--float32", action="store_true")
    a.add_argument("--output", required=True)
    args = a.parse_args()
    points, cells = grid(args.cells, args.lower, args.upper, args.tets)
    write(args.output, points, cells, args.tets, args.kind, args.cell_data, args)


if __name__ == "__main__":
    main()
