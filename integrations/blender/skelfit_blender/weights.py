"""Moving the imported skin weights onto the original object by vertex position."""

import mathutils


def _sources(skinned):
    """World positions and (group name, weight) lists of every vertex of the imported meshes."""
    positions = []
    influences = []
    for obj in skinned:
        names = {group.index: group.name for group in obj.vertex_groups}
        matrix = obj.matrix_world
        for vertex in obj.data.vertices:
            positions.append(matrix @ vertex.co)
            influences.append(
                [(names[g.group], g.weight) for g in vertex.groups if g.weight > 0 and g.group in names]
            )
    return positions, influences


def transfer(skinned, target):
    """Gives every vertex of ``target`` the weights of the nearest vertex of the ``skinned``
    objects (world space; skelfit keeps vertex positions, Blender's importer may split or merge
    vertices). Same-named vertex groups on ``target`` are replaced. Returns the largest
    distance to a matched vertex, in world units."""
    positions, influences = _sources(skinned)
    if not positions:
        raise RuntimeError("the rig skelfit wrote has no skinned vertices")
    tree = mathutils.kdtree.KDTree(len(positions))
    for index, position in enumerate(positions):
        tree.insert(position, index)
    tree.balance()

    names = sorted({name for vertex in influences for name, _ in vertex})
    for name in names:
        existing = target.vertex_groups.get(name)
        if existing is not None:
            target.vertex_groups.remove(existing)
    groups = {name: target.vertex_groups.new(name=name) for name in names}

    matrix = target.matrix_world
    farthest = 0.0
    for vertex in target.data.vertices:
        _, index, distance = tree.find(matrix @ vertex.co)
        farthest = max(farthest, distance)
        for name, weight in influences[index]:
            groups[name].add([vertex.index], weight, "REPLACE")
    return farthest
