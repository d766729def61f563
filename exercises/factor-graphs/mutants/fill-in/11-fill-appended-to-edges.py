# mistake: records each fill edge by appending it to the caller's `edges` list
def fill_in(n, edges, order):
    start = len(edges)
    gone = set()
    for v in order:
        around = sorted({b for a, b in edges if a == v and b not in gone}
                        | {a for a, b in edges if b == v and a not in gone})
        for i, a in enumerate(around):
            for b in around[i + 1:]:
                if [a, b] not in edges and [b, a] not in edges:
                    edges.append([a, b])
        gone.add(v)
    added = len(edges) - start
    return added
