# mistake: records the fill by extending the caller's `edges` list, and counts what it added
def symbolic_fill(n, edges, order):
    start = len(edges)
    done = set()
    for v in order:
        nb = sorted({j for i, j in edges if i == v and j not in done}
                    | {i for i, j in edges if j == v and i not in done})
        joined = {frozenset(e) for e in edges}
        for k, a in enumerate(nb):
            for b in nb[k + 1:]:
                if frozenset((a, b)) not in joined:
                    edges.extend([[a, b]])
                    joined.add(frozenset((a, b)))
        done.add(v)
    return len(edges) - start
