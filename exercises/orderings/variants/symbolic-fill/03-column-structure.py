# method: column structures of L built in order: struct(v) = neighbours of v eliminated later, merged into its parent
def symbolic_fill(n, edges, order):
    position = {v: k for k, v in enumerate(order)}
    later = [set() for _ in range(n)]
    pairs = set()
    for i, j in edges:
        pairs.add((min(i, j), max(i, j)))
        if position[i] < position[j]:
            later[i].add(j)
        else:
            later[j].add(i)
    total = 0
    for v in order:
        struct = later[v]
        total += len(struct)
        if struct:
            parent = min(struct, key=lambda u: position[u])
            later[parent] |= struct - {parent}
    return total - len(pairs)
