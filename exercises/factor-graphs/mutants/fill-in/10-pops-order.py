# mistake: consumes `order` with order.pop(0), so the caller's list is emptied (and a tuple has no pop)
def fill_in(n, edges, order):
    neighbours = {v: set() for v in range(n)}
    for a, b in edges:
        neighbours[a].add(b)
        neighbours[b].add(a)
    added = 0
    while order:
        v = order.pop(0)
        around = sorted(neighbours[v])
        for i, a in enumerate(around):
            for b in around[i + 1:]:
                if b not in neighbours[a]:
                    neighbours[a].add(b)
                    neighbours[b].add(a)
                    added += 1
        for u in around:
            neighbours[u].discard(v)
        neighbours[v].clear()
    return added
