# method: the fill-path theorem: {i, j} is in the filled graph iff a path joins them through variables eliminated before both
def symbolic_fill(n, edges, order):
    position = [0] * n
    for k, v in enumerate(order):
        position[v] = k
    adj = [set() for _ in range(n)]
    for i, j in edges:
        adj[i].add(j)
        adj[j].add(i)
    original = sum(len(s) for s in adj) // 2
    filled = 0
    for i in range(n):
        # search from i through variables eliminated earlier than i; any j reached later than i
        # (or earlier, counted from j's side) with position[j] > position[i] is joined to i
        seen = {i}
        stack = [i]
        reach = set()
        while stack:
            u = stack.pop()
            for w in adj[u]:
                if w in seen:
                    continue
                seen.add(w)
                if position[w] < position[i]:
                    stack.append(w)
                else:
                    reach.add(w)
        filled += len(reach)
    return filled - original
