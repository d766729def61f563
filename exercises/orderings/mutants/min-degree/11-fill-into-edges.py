# mistake: adds the fill pairs to the caller's `edges` list while it eliminates
def min_degree_order(n, edges):
    remaining = list(range(n))
    order = []
    while remaining:
        def degree(v):
            return len({b for a, b in edges if a == v and b in remaining}
                       | {a for a, b in edges if b == v and a in remaining})
        v = min(remaining, key=lambda u: (degree(u), u))
        around = sorted({b for a, b in edges if a == v and b in remaining}
                        | {a for a, b in edges if b == v and a in remaining})
        for i, a in enumerate(around):
            for b in around[i + 1:]:
                edges.append([a, b])
        remaining.remove(v)
        order.append(v)
    return order
