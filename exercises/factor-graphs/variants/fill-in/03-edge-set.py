# method: a global set of frozenset edges; fill-in = edges present at the end minus distinct edges at the start
def fill_in(n, edges, order):
    present = {frozenset(e) for e in edges}
    start = len(present)
    eliminated = set()
    for v in order:
        nb = sorted({u for e in present if v in e for u in e if u != v and u not in eliminated})
        for i, a in enumerate(nb):
            for b in nb[i + 1:]:
                present.add(frozenset((a, b)))
        eliminated.add(v)
    return len(present) - start
