"""Writing a triangle surface as a gmsh ASCII 2.2 mesh, for the mesh
generators beside this file (nodes as (x, y, z), triangles as node numbers
counted from 1)."""


def write_msh(name, nodes, triangles):
    with open(name, "w") as out:
        out.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%d\n" % len(nodes))
        for k, p in enumerate(nodes):
            out.write("%d %.17g %.17g %.17g\n" % (k + 1, p[0], p[1], p[2]))
        out.write("$EndNodes\n$Elements\n%d\n" % len(triangles))
        for k, t in enumerate(triangles):
            out.write("%d 2 2 1 1 %d %d %d\n" % (k + 1, t[0], t[1], t[2]))
        out.write("$EndElements\n")
