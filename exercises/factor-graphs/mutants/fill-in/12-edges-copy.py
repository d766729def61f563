# mistake: copies the edges with edges.copy() before adding the fill to the copy (a tuple has no copy method)
def fill_in(n, edges, order):
    graph = edges.copy()
    added = 0
    for v in order:
        around = sorted({b for a, b in graph if a == v} | {a for a, b in graph if b == v})
        joined = {frozenset((a, b)) for a, b in graph}
        for i, a in enumerate(around):
            for b in around[i + 1:]:
                if frozenset((a, b)) not in joined:
                    graph.append([a, b])
                    joined.add(frozenset((a, b)))
                    added += 1
        graph = [[a, b] for a, b in graph if v not in (a, b)]
    return added
