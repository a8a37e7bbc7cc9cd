"""Lab 12's mistakes table (stereo): realistic wrong implementations, each the
reference solution with one function redefined, the exercise it must lose points in, and
the words its diagnosis must contain (read by ``autograder verify``; see
:mod:`autograder.labs.mistakes`)."""

from . import columns_by_first_axis, reference_def_with

# The reference's DP with the previous column's energy, the backtracking's start and the penalty's scale as given.
_DP = """
        def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):
            s = DEFAULT_SMOOTHNESS if smoothness is None else float(smoothness)
            left, right = _grey_float(left), _grey_float(right)
            D = int(max_disparity) + 1
            costs = _sad_volume(left, right, D - 1, int(block_size))
            if s == 0:
                return np.argmin(costs, axis=2).T.astype(np.float64)
            width = costs.shape[0]
            ramp = ({ramp} * np.arange(D)).astype(np.float32)
            energy = np.empty_like(costs)
            energy[0] = costs[0]
            for x in range(1, width):
                previous = {previous}
                from_below = np.minimum.accumulate(previous - ramp, axis=1) + ramp
                from_above = np.minimum.accumulate((previous + ramp)[:, ::-1], axis=1)[:, ::-1] - ramp
                best = np.minimum(from_below, from_above)
                energy[x] = costs[x] + best - best.min(axis=1, keepdims=True)
            disparity = np.empty((width, costs.shape[1]), dtype=np.int64)
            disparity[-1] = np.argmin({last}, axis=1)
            candidates = np.arange(D)
            for x in range(width - 1, 0, -1):
                jump = ramp[np.abs(candidates[None, :] - disparity[x][:, None])]
                disparity[x - 1] = np.argmin(energy[x - 1] + jump, axis=1)
            return disparity.T.astype(np.float64)
"""

MISTAKES = {
    # the blind set 1206b's 12/04: `mirrored = codes; mirrored.reverse()` reverses the codes too
    "gray_code_patterns reversing an alias of the codes in place": ("lab12.ex6", """
        def gray_code_patterns(width, n_bits):
            width, n_bits = int(width), int(n_bits)
            # binary-reflected Gray codes as bit strings, most significant bit first:
            # G(n) = '0' + each code of G(n-1), then '1' + each code of G(n-1) in reverse order
            codes = ["0", "1"]
            for _ in range(n_bits - 1):
                mirrored = codes
                mirrored.reverse()
                codes = ["0" + c for c in codes] + ["1" + c for c in mirrored]
            patterns = np.zeros((n_bits, width), dtype=np.uint8)
            for u in range(width):
                k = u * 2 ** n_bits // width          # stripe of column u
                for i, bit in enumerate(codes[k]):
                    if bit == "1":
                        patterns[i, u] = 255
            return patterns
        """, ['made it another name for the same list']),
    # the blind set 1206b's 12/03: an alias of a builtin NumPy no longer has
    "simulate_structured_light converting with np.int (removed in NumPy 1.24)": ("lab12.ex6", """
        def simulate_structured_light(depth, f, baseline, n_bits):
            Z = np.asarray(depth, dtype=np.float64)
            height, width = Z.shape
            n_bits = int(n_bits)
            pat = gray_code_patterns(width, n_bits)
            ok = np.isfinite(Z) & (Z > 0)
            disp = np.zeros_like(Z)
            disp[ok] = float(f) * float(baseline) / Z[ok]
            u = np.arange(width)[None, :]
            col = np.floor(u - disp + 0.5).astype(np.int)      # round(u - f b / Z)
            # a column off the projector lights nothing
            ok = ok & (col >= 0) & (col < width)
            images = np.zeros((n_bits, height, width), dtype=np.uint8)
            for i in range(n_bits):
                images[i][ok] = pat[i][col[ok]]
            return images
        """, ['a name NumPy 1.24 removed']),
    # the blind set 1206a's 12/04: u * 2 ** n_bits wraps past 65535
    "gray_code_patterns counting the columns in uint16": ("lab12.ex6", """
        def gray_code_patterns(width, n_bits):
            width, n_bits = int(width), int(n_bits)
            columns = np.arange(width, dtype=np.uint16)
            stripe = columns * 2 ** n_bits // width          # k = floor(u 2^n / width)
            gray = stripe ^ (stripe >> 1)                     # binary-reflected Gray code
            patterns = np.zeros((n_bits, width), dtype=np.uint8)
            for i in range(n_bits):
                bit = (gray >> (n_bits - 1 - i)) & 1          # row 0 = most significant bit
                patterns[i] = 255 * bit
            return patterns
        """, ['dtype=np.int64']),
    # the blind set 1206a's 12/03: OpenCV reads the (D, H, W) volume's last axis as channels
    "dp_stereo box-filtering the whole cost volume with one cv2.blur": ("lab12.ex5", """
        def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):
            s = DEFAULT_SMOOTHNESS if smoothness is None else float(smoothness)
            left, right = _grey_float(left), _grey_float(right)
            D = int(max_disparity) + 1
            height, width = left.shape
            # absolute difference for every candidate d, then its mean over the block
            diffs = np.zeros((D, height, width))
            for d in range(min(D - 1, width - 1) + 1):
                diffs[d] = np.abs(left - _shift_right(right, d))
            block = _box_mean(diffs, int(block_size))
            costs = np.full((D, height, width), 255.0, dtype=np.float32)
            for d in range(min(D - 1, width - 1) + 1):
                costs[d, :, d:] = block[d, :, d:]            # no match where x - d < 0
            costs = np.ascontiguousarray(costs.transpose(2, 1, 0))         # (W, H, D)
            if s == 0:
                return np.argmin(costs, axis=2).T.astype(np.float64)

            width = costs.shape[0]
            ramp = (s * np.arange(D)).astype(np.float32)
            energy = np.empty_like(costs)                 # M(x, d) for every row at once
            energy[0] = costs[0]
            for x in range(1, width):
                previous = energy[x - 1]
                from_below = np.minimum.accumulate(previous - ramp, axis=1) + ramp
                from_above = np.minimum.accumulate((previous + ramp)[:, ::-1], axis=1)[:, ::-1] - ramp
                best = np.minimum(from_below, from_above)
                energy[x] = costs[x] + best - best.min(axis=1, keepdims=True)   # keep the numbers small

            disparity = np.empty((width, costs.shape[1]), dtype=np.int64)
            disparity[-1] = np.argmin(energy[-1], axis=1)
            candidates = np.arange(D)
            for x in range(width - 1, 0, -1):
                jump = ramp[np.abs(candidates[None, :] - disparity[x][:, None])]
                disparity[x - 1] = np.argmin(energy[x - 1] + jump, axis=1)
            return disparity.T.astype(np.float64)
        """, ['for _image in diffs']),
    # the blind set 1206a's 12/02: right[:, :width - d] with d > width keeps all but the last columns
    "block_matching shifting by disparities past the image's width": ("lab12.ex4", """
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            if cost not in ("ssd", "ncc"):
                raise ValueError(f"unknown cost {cost!r}: use 'ssd' or 'ncc'")
            L, Rgt = _grey_float(left), _grey_float(right)
            max_disparity, block_size = int(max_disparity), int(block_size)
            if cost == "ncc":
                volume = _ncc_volume(L, Rgt, max_disparity, block_size)
                return np.argmin(volume, axis=0).astype(np.float64)

            height, width = L.shape
            best_cost = np.full((height, width), np.inf)
            best_d = np.zeros((height, width))
            for d in range(max_disparity + 1):
                # right image moved d columns to the right: shifted[:, x] = right[:, x - d]
                shifted = np.empty_like(Rgt)
                shifted[:, d:] = Rgt[:, :width - d]
                shifted[:, :d] = Rgt[:, :1]
                ssd = _box_mean((L - shifted) ** 2, block_size)
                ssd[:, :d] = np.inf                  # x - d is outside the right image
                better = ssd < best_cost             # strict: ties keep the smaller d
                best_cost[better] = ssd[better]
                best_d[better] = d
            return best_d
        """, ['a negative slice bound counts from the end']),
    # the blind set 1205b's 12/01: both views warped onto a canvas grown to hold them, not the input's size
    "rectify warping onto a canvas grown to hold both views": ("lab12.ex3", reference_def_with(
        "lab12_stereo", "rectify",
        "rect_l = cv2.warpPerspective(np.asarray(img_l), H1, (width, height), flags=cv2.INTER_LINEAR)",
        "corners = np.array([[0.0, 0.0, 1.0], [width - 1.0, 0.0, 1.0], [0.0, height - 1.0, 1.0], [width - 1.0, height - 1.0, 1.0]]).T\n"
        "warped = np.hstack([H1 @ corners, H2 @ corners])\n"
        "warped = warped[:2] / warped[2]\n"
        "x0, y0 = np.floor(warped.min(axis=1))\n"
        "x1, y1 = np.ceil(warped.max(axis=1))\n"
        "offset = np.array([[1.0, 0.0, -x0], [0.0, 1.0, -y0], [0.0, 0.0, 1.0]])\n"
        "H1, H2 = offset @ H1, offset @ H2\n"
        "size = (int(x1 - x0) + 1, int(y1 - y0) + 1)\n"
        "rect_l = cv2.warpPerspective(np.asarray(img_l), H1, size, flags=cv2.INTER_LINEAR)").replace(
            "H2, (width, height)", "H2, size"),
        ["`size` to `(width, height)` (lines"]),
    # the blind set 1204d's 12/08: the decoded stripe index taken as the projector column itself
    "structured light with the stripe index as the projector column": ("lab12.ex6", """
        def depth_from_structured_light(images, f, baseline):
            images = np.asarray(images)
            n_bits, height, width = images.shape
            bits = images > 127
            binary = np.zeros((height, width), dtype=np.int64)
            bit = np.zeros((height, width), dtype=bool)
            for i in range(n_bits):
                bit = bit ^ bits[i]
                binary = binary << 1 | bit
            column = binary.astype(np.float64)
            disparity = np.arange(width)[None, :] - column
            decodable = bits.any(axis=0)
            return np.where(decodable, depth_from_disparity(disparity, f, baseline), 0.0)
        """, ["the stripe index k is used as the projector column"]),
    # the blind set 1204d's 12/05: the module's default read again where the resolved smoothness belongs
    "dp_stereo's penalty ramp from the module default": ("lab12.ex5", _DP.format(
        previous="energy[x - 1]", last="energy[-1]", ramp="DEFAULT_SMOOTHNESS"), ["`s * np.arange(D)`"]),
    # the blind set 1204d's 12/01: the cameras put in left-right order, their points left where they were
    "triangulate exchanging the cameras but not their points": ("lab12.ex1", """
        def triangulate(P1, P2, pts1, pts2):
            P1 = np.asarray(P1, dtype=np.float64)
            P2 = np.asarray(P2, dtype=np.float64)
            pts1 = np.asarray(pts1, dtype=np.float64)
            single = pts1.ndim == 1
            pts1 = pts1.reshape(-1, 2)
            pts2 = np.asarray(pts2, dtype=np.float64).reshape(-1, 2)
            if P2[0, 3] < P1[0, 3]:
                P1, P2 = (P2, P1)
            A = np.stack([pts1[:, :1] * P1[2] - P1[0], pts1[:, 1:] * P1[2] - P1[1],
                          pts2[:, :1] * P2[2] - P2[0], pts2[:, 1:] * P2[2] - P2[1]], axis=1)
            A /= np.linalg.norm(A, axis=2, keepdims=True)
            _, _, Vt = np.linalg.svd(A)
            X = Vt[:, -1]
            X = X[:, :3] / X[:, 3:]
            return X[0] if single else X
        """, ["`P1, P2 = (P2, P1)`"]),   # (the exchange taken out, or made of the points too: both mend it)
    # the blind set 1204d's 12/02: np.vectorize typed by its first value, an int 0 for an invalid pixel
    "depth_from_disparity by np.vectorize returning an int 0": ("lab12.ex2", """
        def depth_from_disparity(disparity, f, baseline):
            rule = np.vectorize(lambda d: f * baseline / d if np.isfinite(d) and d > 0 else 0)
            return rule(np.asarray(disparity, dtype=np.float64))
        """, ["every depth is cut to a whole number"]),
    # the blind set 1204c's 12/04: the rectified frame's third axis taken as the mean optical axis, not e1 x e2
    "rectify's third axis the mean optical axis": ("lab12.ex3", reference_def_with(
        "lab12_stereo", "rectify", "e3 = np.cross(e1, e2)", "e3 = mean_axis / np.linalg.norm(mean_axis)"),
        ["`e3 = np.cross(e1, e2)`"]),
    # the blind set 1204c's 12/03: validity judged against the map's own smallest value, not 0
    "depth_from_disparity valid above the map's minimum": ("lab12.ex2", """
        def depth_from_disparity(disparity, f, baseline):
            d = np.asarray(disparity, dtype=np.float64)
            valid = np.isfinite(d) & (d > np.nanmin(d))
            depth = np.zeros_like(d)
            np.divide(float(f) * float(baseline), d, out=depth, where=valid)
            return depth
        """, ["`np.nanmin(d)` to `0`"]),
    # the blind set 1204c's 12/07: np.digitize's bins counted from 1 (on gray_code_patterns(16, 4) the same
    # patterns as columns numbered from 1: told apart on the probe)
    # the blind set 1204e's 12/06: the patterns' list started with an all-white one (a real scanner's reference)
    # the blind set 1204e's 12/02: invalid pixels filled with the depth of the nearest valid one on their left
    # the blind set 1204e's 12/04: the SSD volume's cells without a partner marked NaN, which np.argmin picks first
    # the blind set 1204e's 12/07: camera x taken relative to the principal point, the centre never added back
    "structured light in coordinates about the centre, never made columns again": ("lab12.ex6", reference_def_with(
        "lab12_stereo", "simulate_structured_light", "u = np.broadcast_to(np.arange(width, dtype=np.float64), depth.shape)",
        "cx = (width - 1) / 2.0\nu = np.broadcast_to(np.arange(width, dtype=np.float64) - cx, depth.shape)"),
        # (the reference's line has no centring: the centring is told as the line's departure from it)
        ["`np.arange(width, dtype=np.float64) - cx` to `np.arange(width, dtype=np.float64)`"]),
    "depth_from_disparity filling the holes from the left": ("lab12.ex2", """
        def depth_from_disparity(disparity, f, baseline):
            d = np.array(disparity, dtype=np.float64)
            valid = np.isfinite(d) & (d > 0)
            depth = np.zeros(d.shape)
            depth[valid] = float(f) * float(baseline) / d[valid]
            source = np.maximum.accumulate(np.where(valid, np.arange(d.shape[-1]), 0), axis=-1)
            return np.take_along_axis(depth, source, axis=-1)
        """, ["`np.take_along_axis(depth, source, axis=-1)` to `depth`"]),
    "structured light reading every pixel's column before leaving the unlit ones out": ("lab12.ex6", reference_def_with(
        "lab12_stereo", "simulate_structured_light", "images[:, lit] = patterns[:, column[lit]]",
        "images = np.where(lit, patterns[:, column], 0).astype(np.uint8)"),
        ["index -480 is out of bounds", "`column` holds -480"]),
    "gray code patterns started with a white one": ("lab12.ex6", """
        def gray_code_patterns(width, n_bits):
            width, n_bits = int(width), int(n_bits)
            k = np.arange(width) * 2 ** n_bits // width
            g = k ^ (k >> 1)
            rows = [np.full(width, 255, dtype=np.uint8)]
            for i in range(n_bits):
                rows.append((((g >> (n_bits - 1 - i)) & 1) * 255).astype(np.uint8))
            return np.array(rows)
        """, ["`[np.full(width, 255, dtype=np.uint8)]` to `[]`"]),
    "gray code stripes by np.digitize, counted from 1": ("lab12.ex6", """
        def gray_code_patterns(width, n_bits):
            width, n_bits = int(width), int(n_bits)
            u = np.arange(width)
            k = np.digitize(u, np.linspace(0, width, 2 ** n_bits + 1))
            gray = k ^ (k >> 1)
            shifts = np.arange(n_bits - 1, -1, -1)[:, None]
            return (((gray[None, :] >> shifts) & 1) * 255).astype(np.uint8)
        """, ["the stripe index is one too large"]),
    # the blind set 1205h's 12/04: rows made least significant bit first, then the columns reversed (fliplr)
    # where the rows' order belongs (flipud)
    "gray_code_patterns reversing the columns where the rows belong": ("lab12.ex6", reference_def_with(
        "lab12_stereo", "gray_code_patterns", "return (((gray[None, :] >> shifts) & 1) * 255).astype(np.uint8)",
        "bits = ((gray[None, :] >> shifts[::-1]) & 1) * 255\nreturn np.fliplr(bits).astype(np.uint8)"),
        ["changing `np.fliplr(bits)` to `np.flipud(bits)`"]),
    # the blind set 1205h's 12/01: scipy's box filter given one size averages the (D, H, W) volume across its
    # disparities too
    "block_matching box-filtering the cost volume along the disparities too": ("lab12.ex4", """
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            from scipy.ndimage import uniform_filter
            left, right = _grey_float(left), _grey_float(right)
            if cost == "ncc":
                return np.argmin(_ncc_volume(left, right, int(max_disparity), int(block_size)), axis=0).astype(float)
            width = left.shape[1]
            volume = np.stack([(left - _shift_right(right, d)) ** 2 for d in range(int(max_disparity) + 1)])
            volume = uniform_filter(volume, size=int(block_size), mode="reflect")
            for d in range(int(max_disparity) + 1):
                volume[d, :, :min(d, width)] = np.inf
            return np.argmin(volume, axis=0).astype(np.float64)
        """, ["to `uniform_filter(volume, size=(1, int("]),
    # the blind set 1204g's 12/02: the search not capped at the image's width (a pair narrower than the range raises)
    "block_matching searching past the image's width": ("lab12.ex4", """
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            left, right = _grey_float(left), _grey_float(right)
            height, width = left.shape
            best, disparity = np.full((height, width), np.inf), np.zeros((height, width))
            for d in range(int(max_disparity) + 1):
                shifted = np.zeros_like(right)
                shifted[:, d:] = right[:, :width - d]
                ssd = _box_mean((left - shifted) ** 2, int(block_size))
                ssd[:, :d] = np.inf
                better = ssd < best
                best[better], disparity[better] = ssd[better], d
            return disparity
        """, ["`shifted[:, d:]`", "(`d` = 13)"]),
    # the blind set 1204c's 12/05: the integral image padded at the end only, so each block sum is the block
    # whose corner is the pixel (the map moved by half a block)
    "block_matching summing blocks from their corner": ("lab12.ex4", """
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            left, right = _grey_float(left), _grey_float(right)
            max_disparity, block_size = int(max_disparity), int(block_size)
            height, width = left.shape
            r = block_size // 2
            best, disparity = np.full((height, width), np.inf), np.zeros((height, width))
            for d in range(min(max_disparity, width - 1) + 1):
                shifted = np.empty_like(right)
                shifted[:, d:], shifted[:, :d] = right[:, :width - d], right[:, :1]
                padded = np.pad((left - shifted) ** 2, ((0, 2 * r), (0, 2 * r)), mode="symmetric")
                integral = np.zeros((padded.shape[0] + 1, padded.shape[1] + 1))
                integral[1:, 1:] = padded.cumsum(axis=0).cumsum(axis=1)
                ssd = (integral[block_size:, block_size:] - integral[:-block_size, block_size:]
                       - integral[block_size:, :-block_size] + integral[:-block_size, :-block_size])
                ssd[:, :d] = np.inf
                better = ssd < best
                best[better], disparity[better] = ssd[better], d
            return disparity
        """, ["the map is moved", "4 px right and 4 px down", "not centred"]),
    # a speed-up keyed by less than the answer depends on: the stripes of the first n_bits asked for a width
    "gray code stripes cached by the width alone": ("lab12.ex6", """
        _STRIPES = {}
        def gray_code_patterns(width, n_bits):
            width, n_bits = int(width), int(n_bits)
            if width not in _STRIPES:
                _STRIPES[width] = (np.arange(width) * (1 << n_bits)) // width
            k = _STRIPES[width]
            gray = k ^ (k >> 1)
            shifts = np.arange(n_bits - 1, -1, -1)[:, None]
            return (((gray[None, :] >> shifts) & 1) * 255).astype(np.uint8)
        """, ["keeps something between calls", "`_STRIPES`"]),
    # the blind set 1201c's 12/04: a 9 x 9 window, but the squared difference of the block means
    # a running minimum kept for the disparity but not for the cost it is compared with
    "block matching whose best cost is overwritten at every disparity": ("lab12.ex4", """
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            volume = (_ssd_volume if cost == "ssd" else _ncc_volume)(
                _grey_float(left), _grey_float(right), int(max_disparity), int(block_size))
            lowest = np.full(volume.shape[1:], np.inf)
            disparity = np.zeros(volume.shape[1:])
            for d, here in enumerate(volume):
                smaller = here < lowest
                disparity[smaller] = d
                lowest = here
            return disparity
        """, ["sets `lowest = here` at every turn", "np.minimum(lowest, here)"]),
    "SSD as the squared difference of the block means": ("lab12.ex4", """
        def _ssd_volume(left, right, max_disparity, block_size):
            height, width = left.shape
            costs = np.full((max_disparity + 1, height, width), np.inf)
            for d in range(min(max_disparity, width - 1) + 1):
                costs[d] = (_box_mean(left, block_size) - _box_mean(_shift_right(right, d), block_size)) ** 2
                costs[d, :, :d] = np.inf
            return costs
        """, ["not that of a smaller window either", "how your cost is computed"]),
    # the blind set 1202f's 12/06: block_size taken as the half-width, a (2 block_size + 1)-wide window
    "block matching with block_size as the window's half-width": ("lab12.ex4", """
        def _ssd_volume(left, right, max_disparity, block_size):
            height, width = left.shape
            costs = np.full((max_disparity + 1, height, width), np.inf)
            for d in range(min(max_disparity, width - 1) + 1):
                costs[d] = _box_mean((left - _shift_right(right, d)) ** 2, 2 * block_size + 1)
                costs[d, :, :d] = np.inf
            return costs
        """, ["a 19 x 19 window (2 block_size + 1"]),
    "block matching squaring the 8-bit differences": ("lab12.ex4", """
        _block_matching_own = block_matching
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            if cost != "ssd":
                return _block_matching_own(left, right, max_disparity, block_size, cost)
            L, R = _grey_float(left).astype(np.uint8), _grey_float(right).astype(np.uint8)
            best = np.full(L.shape, np.inf)
            disparity = np.zeros(L.shape)
            for d in range(min(max_disparity, L.shape[1] - 1) + 1):
                e = cv2.absdiff(L, _shift_right(R, d))
                cost_d = _box_mean(e ** 2, block_size).astype(np.float64)
                cost_d[:, :d] = np.inf
                disparity[cost_d < best] = d
                best = np.minimum(best, cost_d)
            return disparity
        """, ["changing `_box_mean(e ** 2, block_size)` to `_box_mean(e.astype(np.float64) ** 2, block_size)`"]),
    "block matching with block_size ignored": ("lab12.ex4", """
        _block_matching_own = block_matching
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            return _block_matching_own(left, right, max_disparity, 9, cost)
        """, ["block_size is ignored"]),
    # ---------------------------------------------------------------- ex1
    "triangulate with the images swapped": ("lab12.ex1", """
        _triangulate = triangulate
        def triangulate(P1, P2, pts1, pts2):
            return _triangulate(P1, P2, pts2, pts1)
        """, ["swapped"]),
    # the blind set 1203b's 12/01: the points behind camera 1 (wrong matches) dropped, so rows no longer line up
    "triangulate keeping only the points in front (Z > 0)": ("lab12.ex1", """
        _triangulate = triangulate
        def triangulate(P1, P2, pts1, pts2):
            X = _triangulate(P1, P2, pts1, pts2)
            return X[X[:, 2] > 0]
        """, ["left out are exactly the ones whose z is <= 0", "one row per correspondence"]),
    "triangulate with P1 used for both views": ("lab12.ex1", """
        _triangulate = triangulate
        def triangulate(P1, P2, pts1, pts2):
            return _triangulate(P1, P1, pts1, pts2)
        """, ["p1 is used for both views"]),
    "triangulate returns homogeneous points": ("lab12.ex1", """
        def triangulate(P1, P2, pts1, pts2):
            pts1 = np.asarray(pts1, float); pts2 = np.asarray(pts2, float)
            A = np.stack([pts1[:, :1] * P1[2] - P1[0], pts1[:, 1:] * P1[2] - P1[1],
                          pts2[:, :1] * P2[2] - P2[0], pts2[:, 1:] * P2[2] - P2[1]], axis=1)
            return np.linalg.svd(A)[2][:, -1]
        """, ["homogeneous", "fourth coordinate"]),
    "triangulate without the division": ("lab12.ex1", """
        def triangulate(P1, P2, pts1, pts2):
            pts1 = np.asarray(pts1, float); pts2 = np.asarray(pts2, float)
            A = np.stack([pts1[:, :1] * P1[2] - P1[0], pts1[:, 1:] * P1[2] - P1[1],
                          pts2[:, :1] * P2[2] - P2[0], pts2[:, 1:] * P2[2] - P2[1]], axis=1)
            return np.linalg.svd(A)[2][:, -1, :3]
        """, ["fourth coordinate"]),
    "triangulate taking the last row of the batched SVD's Vt (Vt[-1])": ("lab12.ex1", """
        def triangulate(P1, P2, pts1, pts2):
            pts1 = np.asarray(pts1, float).reshape(-1, 2); pts2 = np.asarray(pts2, float).reshape(-1, 2)
            A = np.stack([pts1[:, :1] * P1[2] - P1[0], pts1[:, 1:] * P1[2] - P1[1],
                          pts2[:, :1] * P2[2] - P2[0], pts2[:, 1:] * P2[2] - P2[1]], axis=1)
            _, _, Vt = np.linalg.svd(A)
            X = Vt[-1]
            return X[:, :3] / X[:, 3:]
        """, ["4 rows is the size of each point's 4 x 4 system", "vt[:, -1]"]),
    # One match is an (N, 2) array with N = 1: the (N, 3) answer keeps its row.
    "triangulate squeezing its answer (one match gives (3,))": ("lab12.ex1", """
        def triangulate(P1, P2, pts1, pts2):
            points = []
            for (x1, y1), (x2, y2) in zip(np.asarray(pts1, float), np.asarray(pts2, float)):
                A = np.array([x1 * P1[2] - P1[0], y1 * P1[2] - P1[1], x2 * P2[2] - P2[0], y2 * P2[2] - P2[1]])
                X = np.linalg.svd(A)[2][-1]
                points.append(X[:3] / X[3])
            return np.squeeze(np.array(points))
        """, ["with n=1 returned an array of shape (3,); expected (1, 3)"]),
    "triangulate with OpenCV": ("lab12.ex1", """
        def triangulate(P1, P2, pts1, pts2):
            X = cv2.triangulatePoints(np.float64(P1), np.float64(P2),
                                      np.float64(pts1).T, np.float64(pts2).T)
            return (X[:3] / X[3]).T
        """, ["cv2.triangulatePoints", "yourself"]),
    # ---------------------------------------------------------------- ex2
    # the blind set 1202d's 12/02 and 12/01: a 0-d disparity given an axis; matches off the row dropped
    # the blind set 1203b's 12/02: the divisor clamped to 1, so sub-pixel disparities get the depth f b
    "depth with the disparity clamped to 1": ("lab12.ex2", """
        def depth_from_disparity(disparity, f, baseline):
            d = np.asarray(disparity, dtype=np.float64)
            valid = np.isfinite(d) & (d > 0)
            depth = np.zeros_like(d)
            np.divide(float(f) * float(baseline), np.maximum(d, 1.0), out=depth, where=valid)
            return depth
        """, ["changing `np.maximum(d, 1.0)` to `d`"]),
    "disparity as the distance between the matched points": ("lab12.ex2", """
        _disparity_right = disparity_from_matches
        def disparity_from_matches(xl, xr):
            a, b = np.asarray(xl, dtype=np.float64), np.asarray(xr, dtype=np.float64)
            if a.ndim == 2 and b.ndim == 2:
                return np.linalg.norm(a - b, axis=-1)
            return _disparity_right(xl, xr)
        """, ["changing `np.linalg.norm(a - b, axis=-1)` to `(a - b)[:, 0]`"]),
    "depth of a 0-d disparity given an axis": ("lab12.ex2", """
        _right_depth = depth_from_disparity
        def depth_from_disparity(disparity, f, baseline):
            return _right_depth(np.atleast_1d(np.asarray(disparity, np.float64)), f, baseline)
        """, ["0-d disparity is 0-d too", "np.atleast_1d"]),
    "disparities of matches off the same row dropped": ("lab12.ex2", """
        _right_disparity = disparity_from_matches
        def disparity_from_matches(xl, xr):
            xl, xr = np.asarray(xl, np.float64), np.asarray(xr, np.float64)
            if xl.ndim == 2:
                same_row = np.abs(xl[:, 1] - xr[:, 1]) < 0.5
                xl, xr = xl[same_row], xr[same_row]
            return _right_disparity(xl, xr)
        """, ["none is dropped"]),
    "depth b / (f d)": ("lab12.ex2", """
        def depth_from_disparity(disparity, f, baseline):
            d = np.asarray(disparity, float)
            ok = np.isfinite(d) & (d > 0)
            return np.where(ok, baseline / (f * np.where(ok, d, 1.0)), 0.0)
        """, ["b / (f d)"]),
    "depth in millimetres (the baseline converted, the depth not back)": ("lab12.ex2", """
        _depth_from_disparity = depth_from_disparity
        def depth_from_disparity(disparity, f, baseline):
            return _depth_from_disparity(disparity, f, baseline * 1000.0)
        """, ["the depths are 1000 times the expected"]),
    # An integer map (a matcher's int16, an argmin's int64): the depth array made like it is integer.
    # a mask of the valid disparities made, used, and first made a reason to refuse the map
    "depth_from_disparity refusing a map with holes": ("lab12.ex2", """
        def depth_from_disparity(disparity, f, baseline):
            d = np.asarray(disparity, dtype=np.float64)
            ok = np.isfinite(d) & (d > 0)
            if not np.all(ok):
                raise ValueError("invalid disparities")
            return np.where(ok, f * baseline / np.where(ok, d, 1.0), 0.0)
        """, ["removing `if not np.all(ok): raise ...`"]),
    "depth into np.zeros_like(disparity): an integer map raises": ("lab12.ex2", """
        def depth_from_disparity(disparity, f, baseline):
            depth = np.zeros_like(disparity)
            np.divide(f * baseline, disparity, out=depth, where=disparity > 0)
            return depth
        """, ["raised", "the depth array takes the disparity's integer dtype", "np.zeros_like"]),
    "depth assigned into np.zeros_like(disparity): integer depths": ("lab12.ex2", """
        def depth_from_disparity(disparity, f, baseline):
            d = np.asarray(disparity)
            depth = np.zeros_like(d)
            valid = d > 0
            depth[valid] = f * baseline / d[valid]
            return depth
        """, ["returned depths of dtype int16", "the depth array takes the disparity's integer dtype"]),
    "depth inf where d = 0": ("lab12.ex2", """
        def depth_from_disparity(disparity, f, baseline):
            with np.errstate(divide="ignore", invalid="ignore"):
                return f * baseline / np.asarray(disparity, float)
        """, ["where the disparity is 0, your depth is inf", "must be 0"]),
    "depth f b / (d + eps): huge but finite where d = 0": ("lab12.ex2", """
        def depth_from_disparity(disparity, f, baseline):
            d = np.nan_to_num(np.asarray(disparity, float))
            return f * baseline / (np.abs(d) + 1e-9)
        """, ["where the disparity is 0, your depth is 8e+10", "where the disparity is negative, your depth is"]),
    "depth negative for negative disparities": ("lab12.ex2", """
        def depth_from_disparity(disparity, f, baseline):
            d = np.asarray(disparity, float)
            ok = np.isfinite(d) & (d != 0)
            return np.where(ok, f * baseline / np.where(ok, d, 1.0), 0.0)
        """, ["where the disparity is negative, your depth is -26.7", "must be 0"]),
    # The sheet shows the disparity map after the depth is computed from it (engine/inplace.py's
    # shown_after): invalid entries overwritten in the caller's map lose points, with no second call.
    "depth marking the caller's invalid disparities NaN in place (np.asarray: no copy)": ("lab12.ex2", """
        def depth_from_disparity(disparity, f, baseline):
            d = np.asarray(disparity, dtype=np.float64)
            d[~(d > 0)] = np.nan
            depth = f * baseline / d
            return np.where(np.isnan(depth), 0.0, depth)
        """, ["writes into the caller's `disparity` in place", "0 became nan", "shows or uses `disparity` after"]),
    "disparity xr - xl": ("lab12.ex2", """
        def disparity_from_matches(xl, xr):
            xl = np.asarray(xl, float); xr = np.asarray(xr, float)
            if xl.ndim == 2:
                xl, xr = xl[:, 0], xr[:, 0]
            return xr - xl
        """, ["wrong sign"]),
    # d = x_l - x_r keeps its sign: a mismatch (x_r > x_l) gives a negative disparity.
    "disparity as a distance |x_l - x_r|": ("lab12.ex2", """
        def disparity_from_matches(xl, xr):
            xl = np.asarray(xl, float); xr = np.asarray(xr, float)
            if xl.ndim == 2:
                xl, xr = xl[:, 0], xr[:, 0]
            return np.abs(xl - xr)
        """, ["where x_r > x_l (x_l = 12, x_r = 19.5) it returned 7.5, not -7.5", "every disparity came back positive"]),
    "disparity from the y column": ("lab12.ex2", """
        def disparity_from_matches(xl, xr):
            xl = np.asarray(xl, float); xr = np.asarray(xr, float)
            if xl.ndim == 2:
                xl, xr = xl[:, 1], xr[:, 1]
            return xl - xr
        """, ["y coordinates"]),
    # the blind set 29d's 12/01: points told from x coordinates by the last axis's length, not the dimensions
    "disparity_from_matches taking any last axis of length 2 for (x, y) points": ("lab12.ex2", """
        def disparity_from_matches(xl, xr):
            def x_of(a):
                a = np.asarray(a, dtype=np.float64)
                return a[..., 0] if a.shape[-1] == 2 else a
            return x_of(xl) - x_of(xr)
        """, ["returned the single number", "as if the two x coordinates were one (x, y) point"]),
    "depth with d and b swapped (f d / b)": ("lab12.ex2", """
        def depth_from_disparity(disparity, f, baseline):
            d = np.asarray(disparity, float)
            ok = np.isfinite(d) & (d > 0)
            return np.where(ok, f * np.where(ok, d, 1.0) / baseline, 0.0)
        """, ["d and b are swapped"]),
    # ---------------------------------------------------------------- ex3
    "rectify a colour pair into grey (made grey for stereo first)": ("lab12.ex3", """
        _rectify = rectify
        def rectify(img_l, img_r, K1, K2, R, T):
            if img_l.ndim == 3:
                img_l, img_r = cv2.cvtColor(img_l, cv2.COLOR_BGR2GRAY), cv2.cvtColor(img_r, cv2.COLOR_BGR2GRAY)
            return _rectify(img_l, img_r, K1, K2, R, T)
        """, ["channels are not kept", "BGR in, BGR out"]),
    # the blind set 1202e's 12/04: the rotation brings in pixels from beyond the frame, filled from its edge
    "rectify warping with the homographies' first two rows (an affine warp)": ("lab12.ex3", """
        _rectify_right = rectify
        def rectify(img_l, img_r, K1, K2, R, T):
            _, _, H1, H2 = _rectify_right(img_l, img_r, K1, K2, R, T)
            size = (np.asarray(img_l).shape[1], np.asarray(img_l).shape[0])
            left = cv2.warpAffine(np.asarray(img_l), H1[:2], size)
            right = cv2.warpAffine(np.asarray(img_r), H2[:2], size)
            return left, right, H1, H2
        """, ["to `cv2.warpPerspective(np.asarray(img_l), H1, size)`"]),
    "rectify warping with cv2.BORDER_REPLICATE": ("lab12.ex3", """
        _rectify = rectify
        def rectify(img_l, img_r, K1, K2, R, T):
            a, b, H1, H2 = _rectify(img_l, img_r, K1, K2, R, T)
            h, w = np.asarray(img_l).shape[:2]
            return (cv2.warpPerspective(np.asarray(img_l), H1, (w, h), borderMode=cv2.BORDER_REPLICATE),
                    cv2.warpPerspective(np.asarray(img_r), H2, (w, h), borderMode=cv2.BORDER_REPLICATE), H1, H2)
        """, ["are not black", "your code uses cv2.BORDER_REPLICATE"]),
    # the blind set 1202g's 12/03: cv2.stereoRectify with flags=0, each camera its own principal point
    "rectify by cv2.stereoRectify without CALIB_ZERO_DISPARITY": ("lab12.ex3", """
        def rectify(img_l, img_r, K1, K2, R, T):
            K1 = np.asarray(K1, float); K2 = np.asarray(K2, float)
            h, w = np.asarray(img_l).shape[:2]
            R1, R2, P1, P2, _, _, _ = cv2.stereoRectify(K1, np.zeros(5), K2, np.zeros(5), (w, h), np.asarray(R, float),
                                                        np.asarray(T, float).reshape(3, 1), flags=0, alpha=0)
            H1 = P1[:, :3] @ R1 @ np.linalg.inv(K1)
            H2 = P2[:, :3] @ R2 @ np.linalg.inv(K2)
            return (cv2.warpPerspective(np.asarray(img_l), H1, (w, h)), cv2.warpPerspective(np.asarray(img_r), H2, (w, h)),
                    H1, H2)
        """, ["principal points differ", "without cv2.CALIB_ZERO_DISPARITY"]),
    "rectify returns inverse homographies": ("lab12.ex3", """
        _rectify = rectify
        def rectify(img_l, img_r, K1, K2, R, T):
            a, b, H1, H2 = _rectify(img_l, img_r, K1, K2, R, T)
            return a, b, np.linalg.inv(H1), np.linalg.inv(H2)
        """, ["back to the originals"]),
    # the blind set 29d's 12/03: the images warped right, stereoRectify's rotations returned
    "rectify returning the rectifying rotations R1, R2 as H1, H2": ("lab12.ex3", """
        def rectify(img_l, img_r, K1, K2, R, T):
            K1 = np.asarray(K1, float); K2 = np.asarray(K2, float)
            h, w = np.asarray(img_l).shape[:2]
            R1, R2, P1, P2, _, _, _ = cv2.stereoRectify(K1, np.zeros(5), K2, np.zeros(5), (w, h), np.asarray(R, float),
                                                        np.asarray(T, float).reshape(3, 1),
                                                        flags=cv2.CALIB_ZERO_DISPARITY, alpha=-1)
            H1 = P1[:, :3] @ R1 @ np.linalg.inv(K1)
            H2 = P2[:, :3] @ R2 @ np.linalg.inv(K2)
            rect_l = cv2.warpPerspective(np.asarray(img_l), H1, (w, h))
            rect_r = cv2.warpPerspective(np.asarray(img_r), H2, (w, h))
            return rect_l, rect_r, R1, R2
        """, ["rotation matrices (orthonormal, determinant 1)", "the rectifying rotations are returned as H1 and H2"]),
    "rectify warping with cv2.WARP_INVERSE_MAP (the homographies applied the other way round)": ("lab12.ex3", """
        _rectify = rectify
        def rectify(img_l, img_r, K1, K2, R, T):
            a, b, H1, H2 = _rectify(img_l, img_r, K1, K2, R, T)
            h, w = np.asarray(img_l).shape[:2]
            flags = cv2.INTER_LINEAR | cv2.WARP_INVERSE_MAP
            return (cv2.warpPerspective(np.asarray(img_l), H1, (w, h), flags=flags),
                    cv2.warpPerspective(np.asarray(img_r), H2, (w, h), flags=flags), H1, H2)
        """, ["warped by the inverse of your H1"]),
    "rectify with the homographies swapped": ("lab12.ex3", """
        _rectify = rectify
        def rectify(img_l, img_r, K1, K2, R, T):
            a, b, H1, H2 = _rectify(img_l, img_r, K1, K2, R, T)
            return a, b, H2, H1
        """, ["swapped"]),
    "rectify with the pose read backwards": ("lab12.ex3", """
        _rectify = rectify
        def rectify(img_l, img_r, K1, K2, R, T):
            R = np.asarray(R, float)
            return _rectify(img_l, img_r, K1, K2, R.T, -R.T @ np.asarray(T, float))
        """, ["the pose is read backwards"]),
    "rectify with the baseline reversed": ("lab12.ex3", """
        _rectify = rectify
        def rectify(img_l, img_r, K1, K2, R, T):
            flip = np.diag([-1.0, -1.0, 1.0])
            a, b, H1, H2 = _rectify(img_l, img_r, K1, K2, R, T)
            return a, b, flip @ H1, flip @ H2
        """, ["negative"]),
    "rectify pushes the images out of view": ("lab12.ex3", """
        _rectify = rectify
        def rectify(img_l, img_r, K1, K2, R, T):
            shift = np.array([[1.0, 0, 110], [0, 1, 0], [0, 0, 1]])
            a, b, H1, H2 = _rectify(img_l, img_r, K1, K2, R, T)
            H1, H2 = shift @ H1, shift @ H2
            size = (img_l.shape[1], img_l.shape[0])
            return cv2.warpPerspective(img_l, H1, size), cv2.warpPerspective(img_r, H2, size), H1, H2
        """, ["stays inside"]),
    "rectified images do not match the homographies": ("lab12.ex3", """
        _rectify = rectify
        def rectify(img_l, img_r, K1, K2, R, T):
            a, b, H1, H2 = _rectify(img_l, img_r, K1, K2, R, T)
            return np.array(img_l), np.array(img_r), H1, H2
        """, ["differs from the input warped"]),
    "rectify with the rectified images swapped": ("lab12.ex3", """
        _rectify = rectify
        def rectify(img_l, img_r, K1, K2, R, T):
            a, b, H1, H2 = _rectify(img_l, img_r, K1, K2, R, T)
            return b, a, H1, H2
        """, ["rect_l and rect_r are swapped"]),
    "rectify with R transposed": ("lab12.ex3", """
        _rectify = rectify
        def rectify(img_l, img_r, K1, K2, R, T):
            return _rectify(img_l, img_r, K1, K2, np.asarray(R, float).T, T)
        """, ["r is transposed inside your function"]),
    "rectify with K where K^-1 belongs": ("lab12.ex3", """
        def rectify(img_l, img_r, K1, K2, R, T):
            K1 = np.asarray(K1, float); K2 = np.asarray(K2, float)
            R = np.asarray(R, float); T = np.asarray(T, float).reshape(3)
            h, w = np.asarray(img_l).shape[:2]
            e1 = -R.T @ T / np.linalg.norm(T)
            e2 = np.cross(np.array([0, 0, 1.0]) + R.T @ np.array([0, 0, 1.0]), e1)
            e2 /= np.linalg.norm(e2)
            R_rect = np.vstack([e1, e2, np.cross(e1, e2)])
            K_new = np.array([[K1[0, 0], 0, w / 2], [0, K1[0, 0], h / 2], [0, 0, 1.0]])
            H1, H2 = K_new @ R_rect @ K1, K_new @ R_rect @ R.T @ K2
            return cv2.warpPerspective(img_l, H1, (w, h)), cv2.warpPerspective(img_r, H2, (w, h)), H1, H2
        """, ["k is used where k^-1 belongs"]),
    "rectify with the third axis crossed the other way (e3 = e2 x e1)": ("lab12.ex3", """
        def rectify(img_l, img_r, K1, K2, R, T):
            K1 = np.asarray(K1, float); K2 = np.asarray(K2, float)
            R = np.asarray(R, float); T = np.asarray(T, float).reshape(3)
            h, w = np.asarray(img_l).shape[:2]
            e1 = -R.T @ T / np.linalg.norm(T)
            e2 = np.cross(np.array([0, 0, 1.0]) + R.T @ np.array([0, 0, 1.0]), e1)
            e2 /= np.linalg.norm(e2)
            R_rect = np.vstack([e1, e2, np.cross(e2, e1)])
            K_new = np.array([[K1[0, 0], 0, w / 2], [0, K1[0, 0], h / 2], [0, 0, 1.0]])
            H1, H2 = K_new @ R_rect @ np.linalg.inv(K1), K_new @ R_rect @ R.T @ np.linalg.inv(K2)
            return cv2.warpPerspective(img_l, H1, (w, h)), cv2.warpPerspective(img_r, H2, (w, h)), H1, H2
        """, ["third axis alone points the opposite way"]),
    # ---------------------------------------------------------------- ex4
    "block matching in the wrong direction": ("lab12.ex4", """
        def _shift_right(image, d):
            if d == 0:
                return image
            out = np.empty_like(image)
            out[:, :-d] = image[:, d:]
            out[:, -d:] = image[:, -1:]
            return out

        def _ssd_volume(left, right, max_disparity, block_size):
            height, width = left.shape
            costs = np.full((max_disparity + 1, height, width), np.inf)
            for d in range(max_disparity + 1):
                costs[d] = _box_mean((left - _shift_right(right, d)) ** 2, block_size)
                if d:
                    costs[d, :, -d:] = np.inf
            return costs
        """, ["wrong direction"]),
    "block matching with negative disparities": ("lab12.ex4", """
        _block_matching = block_matching
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            return -_block_matching(left, right, max_disparity, block_size, cost)
        """, ["negative"]),
    "block matching off by one": ("lab12.ex4", """
        _block_matching = block_matching
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            return _block_matching(left, right, max_disparity, block_size, cost) + 1
        """, ["off by"]),
    "block matching that never searches d = 0": ("lab12.ex4", """
        _ssd = _ssd_volume
        def _ssd_volume(left, right, max_disparity, block_size):
            costs = _ssd(left, right, max_disparity, block_size)
            costs[0] = np.inf
            return costs
        """, ["wall at infinity", "must include d = 0"]),
    "block matching searching half the range (max_disparity // 2)": ("lab12.ex4", """
        _block_matching = block_matching
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            return _block_matching(left, right, max_disparity // 2, block_size, cost)
        """, ["of the wrong disparities are too small", "your largest disparity is"]),
    "block matching with StereoBM's fixed point kept": ("lab12.ex4", """
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            n = 16 * -(-(max_disparity + 1) // 16)
            d = cv2.StereoBM_create(numDisparities=n, blockSize=block_size).compute(left, right)
            return np.where((d > 0) & (d <= 16 * max_disparity), d, 0).astype(np.float64)
        """, ["fixed-point", "never divides its answer by 16"]),
    "block matching with StereoBM's fixed point kept, then values above max_disparity set to 0": ("lab12.ex4", """
        _block_matching_own = block_matching
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            if cost != "ssd":
                return _block_matching_own(left, right, max_disparity, block_size, cost)
            stereo = cv2.StereoBM_create(numDisparities=16 * -(-(max_disparity + 1) // 16), blockSize=block_size)
            d = stereo.compute(left, right).astype(np.float32)
            d[d > max_disparity] = 0
            return d
        """, ["of the pixels get a disparity", "never divides its answer by 16"]),
    "block matching with StereoBM's fixed point kept, clipped to max_disparity": ("lab12.ex4", """
        _block_matching_own = block_matching
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            if cost != "ssd":
                return _block_matching_own(left, right, max_disparity, block_size, cost)
            stereo = cv2.StereoBM_create(numDisparities=16 * ((max_disparity + 16) // 16), blockSize=block_size)
            return np.clip(stereo.compute(left, right).astype(np.float32), 0, max_disparity)
        """, ["of your valid disparities are max_disparity", "never divides its answer by 16"]),
    "block matching with StereoBM's int16 fixed point converted to float32 only": ("lab12.ex4", """
        _block_matching_own = block_matching
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            if cost != "ssd":
                return _block_matching_own(left, right, max_disparity, block_size, cost)
            stereo = cv2.StereoBM_create(numDisparities=16 * int(np.ceil((max_disparity + 1) / 16)),
                                         blockSize=block_size)
            disparity = np.float32(stereo.compute(left, right))
            disparity[disparity < 0] = 0
            return disparity
        """, ["fixed-point", "never divides its answer by 16"]),
    "block matching returning twice the disparity": ("lab12.ex4", """
        _block_matching = block_matching
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            return 2.0 * _block_matching(left, right, max_disparity, block_size, cost)
        """, ["the disparities are twice the expected"]),
    "block_size ignored (a fixed 31 x 31 block)": ("lab12.ex4", """
        _block_matching = block_matching
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            return _block_matching(left, right, max_disparity, 31, cost)
        """, ["block_size=5 and block_size=15 give the same disparity map: block_size is ignored"]),
    "block matching keeping the highest SSD (argmax)": ("lab12.ex4", """
        _ssd = _ssd_volume
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            volume = _ssd(_grey_float(left), _grey_float(right), int(max_disparity), int(block_size))
            volume[~np.isfinite(volume)] = -np.inf
            return np.argmax(volume, axis=0).astype(np.float64)
        """, ["the disparity with the highest ssd is kept"]),
    # ---------------------------------------------------------------- ext1
    "NCC without subtracting the means": ("lab12.ext1", """
        def _ncc_volume(left, right, max_disparity, block_size):
            height, width = left.shape
            energy_l = _box_mean(left * left, block_size)
            costs = np.full((max_disparity + 1, height, width), np.inf)
            for d in range(max_disparity + 1):
                shifted = _shift_right(right, d)
                energy_r = _box_mean(shifted * shifted, block_size)
                costs[d] = -_box_mean(left * shifted, block_size) / np.sqrt(energy_l * energy_r + 1e-9)
                costs[d, :, :d] = np.inf
            return costs
        """, ["not fully normalised"]),
    "NCC as a plain correlation": ("lab12.ext1", """
        def _ncc_volume(left, right, max_disparity, block_size):
            height, width = left.shape
            costs = np.full((max_disparity + 1, height, width), np.inf)
            for d in range(max_disparity + 1):
                costs[d] = -_box_mean(left * _shift_right(right, d), block_size)
                costs[d, :, :d] = np.inf
            return costs
        """, ["fails even when both views have the same brightness"]),
    "block_matching with the two costs swapped": ("lab12.ext1", """
        _block_matching = block_matching
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            other = {"ssd": "ncc", "ncc": "ssd"}.get(cost, cost)
            return _block_matching(left, right, max_disparity, block_size, other)
        """, ["the two costs are swapped"]),
    "NCC with block_size ignored (a fixed 21 x 21 block)": ("lab12.ext1", """
        _block_matching = block_matching
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            return _block_matching(left, right, max_disparity, 21, cost)
        """, ["block_size=5 and block_size=15 give the same disparity map: block_size is ignored"]),
    "cost argument ignored": ("lab12.ext1", """
        _block_matching = block_matching
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            return _block_matching(left, right, max_disparity, block_size, "ssd")
        """, ["cost argument is ignored"]),
    "NCC keeping the lowest score (argmin of the similarity)": ("lab12.ext1", """
        _ncc = _ncc_volume
        def _ncc_volume(left, right, max_disparity, block_size):
            costs = -_ncc(left, right, max_disparity, block_size)
            costs[~np.isfinite(costs)] = np.inf
            return costs
        """, ["the disparity with the lowest ncc is kept"]),
    # the blind set 1202i's 12/04: no guard for flat blocks, 0/0 = NaN wins np.argmin
    "NCC without a guard for flat blocks": ("lab12.ext1", """
        def _ncc_volume(left, right, max_disparity, block_size):
            height, width = left.shape
            mean_l = _box_mean(left, block_size)
            std_l = np.sqrt(np.maximum(_box_mean(left * left, block_size) - mean_l ** 2, 0.0))
            costs = np.full((max_disparity + 1, height, width), np.inf)
            for d in range(min(max_disparity, width - 1) + 1):
                shifted = _shift_right(right, d)
                mean_r = _box_mean(shifted, block_size)
                std_r = np.sqrt(np.maximum(_box_mean(shifted * shifted, block_size) - mean_r ** 2, 0.0))
                covariance = _box_mean(left * shifted, block_size) - mean_l * mean_r
                with np.errstate(invalid="ignore", divide="ignore"):
                    costs[d] = -covariance / (std_l * std_r)
                costs[d, :, :d] = np.inf
            return costs
        """, ["np.argmin takes nan as the lowest cost"]),
    "NCC divided by the variances": ("lab12.ext1", """
        def _ncc_volume(left, right, max_disparity, block_size):
            height, width = left.shape
            mean_l = _box_mean(left, block_size)
            var_l = np.maximum(_box_mean(left * left, block_size) - mean_l ** 2, 0.0)
            costs = np.full((max_disparity + 1, height, width), np.inf)
            for d in range(max_disparity + 1):
                shifted = _shift_right(right, d)
                mean_r = _box_mean(shifted, block_size)
                var_r = np.maximum(_box_mean(shifted * shifted, block_size) - mean_r ** 2, 0.0)
                covariance = _box_mean(left * shifted, block_size) - mean_l * mean_r
                costs[d] = -np.divide(covariance, var_l * var_r, out=np.zeros_like(covariance),
                                      where=var_l * var_r > 1e-6)
                costs[d, :, :d] = np.inf
            return costs
        """, ["the ncc is divided by the right block's variance"]),
    "block matching shifting the left image the wrong way (np.roll(L, -d))": ("lab12.ex4", """
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            L, R = _grey_float(left), _grey_float(right)
            h, w = L.shape
            best, disp = np.full((h, w), np.inf), np.zeros((h, w))
            for d in range(min(int(max_disparity), w - 1) + 1):
                ssd = _box_mean((np.roll(L, -d, axis=1) - R) ** 2, int(block_size))
                ssd[:, w - d:] = np.inf
                better = ssd < best
                disp[better], best[better] = d, ssd[better]
            return disp
        """, ["your code shifts the left image", "a map of the right image's pixels"]),
    # (the left band is judged where a DP's scene judges it: the deep step's failure is its impossible matches)
    "DP whose cost volume gives impossible matches (x < d) cost 0": ("lab12.ex5", """
        def _sad_volume(left, right, max_disparity, block_size):
            height, width = left.shape
            costs = np.zeros((max_disparity + 1, height, width), dtype=np.float32)
            for d in range(min(max_disparity, width - 1) + 1):
                costs[d, :, d:] = _box_mean(np.abs(left - _shift_right(right, d)), block_size)[:, d:]
            return np.ascontiguousarray(costs.transpose(2, 1, 0))
        """, ["get a disparity larger than their column x", "d = 0..min(x, max_disparity)"]),
    "DP without smoothness (winner-take-all)": ("lab12.ex5", """
        DEFAULT_SMOOTHNESS = 0.0
        """, ["the smoothness term is ignored (winner-take-all)"]),
    "DP that ignores the smoothness argument": ("lab12.ex5", """
        _dp_stereo = dp_stereo
        def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):
            return _dp_stereo(left, right, max_disparity, block_size, None)
        """, ["smoothness=0 and smoothness=10000000.0 give the same disparity map: smoothness is ignored"]),
    "DP taking smoothness=0 for the default (smoothness or DEFAULT)": ("lab12.ex5", """
        _dp_stereo = dp_stereo
        def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):
            smoothness = smoothness or DEFAULT_SMOOTHNESS
            return _dp_stereo(left, right, max_disparity, block_size, smoothness)
        """, ["gives exactly the map of smoothness=none", "smoothness=0 is taken for the default"]),
    "DP taking smoothness=0 for the default (if not smoothness)": ("lab12.ex5", """
        _dp_stereo = dp_stereo
        def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):
            if not smoothness:
                smoothness = DEFAULT_SMOOTHNESS
            return _dp_stereo(left, right, max_disparity, block_size, smoothness)
        """, ["smoothness=0 is taken for the default"]),
    "DP whose last column is always 0": ("lab12.ex5", """
        _dp_stereo = dp_stereo
        def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):
            disparity = _dp_stereo(left, right, max_disparity, block_size, smoothness)
            disparity[:, -1] = 0
            return disparity
        """, ["the last column", "backtracking"]),
    "DP with SGBM": ("lab12.ex5", """
        def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):
            sgbm = cv2.StereoSGBM_create(0, 16 * ((max_disparity + 15) // 16), block_size)
            return sgbm.compute(left, right).astype(np.float64) / 16
        """, ["cv2.StereoSGBM_create", "yourself"]),
    "DP backtracking that never fills the last column": ("lab12.ex5", """
        _dp_stereo = dp_stereo
        def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):
            disparity = _dp_stereo(left, right, max_disparity, block_size, smoothness)
            shifted = np.zeros_like(disparity)
            shifted[:, :-1] = disparity[:, 1:]
            return shifted
        """, ["the last column", "where the backtracking starts, is wrong"]),
    "DP with its block fixed at 5 x 5 (block_size ignored)": ("lab12.ex5", """
        _sad = _sad_volume
        def _sad_volume(left, right, max_disparity, block_size):
            return _sad(left, right, max_disparity, 5)
        """, ["block_size=3 and block_size=9 give the same disparity map: block_size is ignored"]),
    # the blind set 1202c's 12/08: the recurrence reads the previous column's data cost
    "DP whose forward pass carries the previous column's data cost": ("lab12.ex5", _DP.format(ramp="s",
        previous="costs[x - 1]", last="energy[-1]"), ["is computed from `costs[x - 1]` and never from `energy` at x - 1"]),
    "DP whose backtracking starts from the last column's least data cost": ("lab12.ex5", _DP.format(ramp="s",
        previous="energy[x - 1]", last="costs[-1]"), ["decided by its last columns alone"]),
    # (the blind set 1202d's 12/05 left np.empty_like's memory in a column: answers that vary from call to call)
    "DP leaving a few pixels at random unset": ("lab12.ex5", """
        _right_dp = dp_stereo
        def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):
            disparity = _right_dp(left, right, max_disparity, block_size, smoothness)
            return np.where(np.random.uniform(size=disparity.shape) < 0.002, 0.0, disparity)
        """, ["called twice, gives two different"]),
    "DP with a default smoothness far too large": ("lab12.ex5", """
        DEFAULT_SMOOTHNESS = 400.0
        """, ["the default smoothness is far too large"]),
    # ---------------------------------------------------------------- ex6
    # the blind set 1202d's 12/06: u = 1 .. width
    "Gray-code columns numbered from 1": ("lab12.ex6", """
        def gray_code_patterns(width, n_bits):
            u = np.arange(1, int(width) + 1)
            k = (u * (1 << int(n_bits))) // int(width)
            gray = k ^ (k >> 1)
            bits = (gray[None, :] >> np.arange(int(n_bits) - 1, -1, -1)[:, None]) & 1
            return (bits * 255).astype(np.uint8)
        """, ["the columns are numbered from 1"]),
    "patterns of (g >> s) & 1 * 255 (the & taken after the *)": ("lab12.ex6", """
        def gray_code_patterns(width, n_bits):
            u = np.arange(int(width))
            k = (u * (1 << int(n_bits))) // int(width)
            gray = k ^ (k >> 1)
            shifts = np.arange(int(n_bits) - 1, -1, -1)[:, None]
            return ((gray[None, :] >> shifts) & 1 * 255).astype(np.uint8)
        """, ["row i is (g >> s) & 255", "binds tighter than &"]),
    "structured light with the disparity f / (b Z)": ("lab12.ex6", """
        _simulate = simulate_structured_light
        def simulate_structured_light(depth, f, baseline, n_bits):
            return _simulate(depth, f, 1.0 / baseline, n_bits)
        """, ["a disparity f / (b Z) where f b / Z belongs"]),
    "plain binary patterns": ("lab12.ex6", """
        def gray_code_patterns(width, n_bits):
            k = (np.arange(width) * 2**n_bits) // width
            shifts = np.arange(n_bits - 1, -1, -1)[:, None]
            return (((k[None, :] >> shifts) & 1) * 255).astype(np.uint8)
        """, ["plain binary"]),
    "patterns least significant bit first": ("lab12.ex6", """
        _gray_code_patterns = gray_code_patterns
        def gray_code_patterns(width, n_bits):
            return _gray_code_patterns(width, n_bits)[::-1]
        """, ["wrong order"]),
    "projector on the wrong side": ("lab12.ex6", """
        def simulate_structured_light(depth, f, baseline, n_bits):
            depth = np.asarray(depth, float)
            height, width = depth.shape
            patterns = gray_code_patterns(width, n_bits)
            valid = depth > 0
            d = np.divide(f * baseline, depth, out=np.zeros_like(depth), where=valid)
            column = np.floor(np.arange(width) + d + 0.5).astype(int)
            lit = valid & (column >= 0) & (column < width)
            images = np.zeros((n_bits, height, width), np.uint8)
            images[:, lit] = patterns[:, column[lit]]
            return images
        """, ["u - f b / z"]),
    "projector's last column taken as off the projector (column < width - 1)": ("lab12.ex6", """
        def simulate_structured_light(depth, f, baseline, n_bits):
            depth = np.asarray(depth, float)
            height, width = depth.shape
            patterns = gray_code_patterns(width, n_bits)
            valid = depth > 0
            d = np.divide(f * baseline, depth, out=np.zeros_like(depth), where=valid)
            column = np.floor(np.arange(width) - d + 0.5).astype(int)
            lit = valid & (column >= 0) & (column < width - 1)
            images = np.zeros((n_bits, height, width), np.uint8)
            images[:, lit] = patterns[:, column[lit]]
            return images
        """, ["projector's last column (width - 1) lights nothing"]),
    "projector column truncated": ("lab12.ex6", """
        def simulate_structured_light(depth, f, baseline, n_bits):
            depth = np.asarray(depth, float)
            height, width = depth.shape
            patterns = gray_code_patterns(width, n_bits)
            valid = depth > 0
            d = np.divide(f * baseline, depth, out=np.zeros_like(depth), where=valid)
            column = (np.arange(width) - d).astype(int)
            lit = valid & (column >= 0) & (column < width)
            images = np.zeros((n_bits, height, width), np.uint8)
            images[:, lit] = patterns[:, column[lit]]
            return images
        """, ["truncated"]),
    "decoding without Gray to binary": ("lab12.ex6", """
        def depth_from_structured_light(images, f, baseline):
            images = np.asarray(images)
            n, height, width = images.shape
            k = np.zeros((height, width), int)
            for image in images:
                k = (k << 1) | (image > 127)
            column = (k + 0.5) * width / 2**n - 0.5
            z = depth_from_disparity(np.arange(width) - column, f, baseline)
            return np.where((images > 127).any(axis=0), z, 0.0)
        """, ["plain binary"]),
    "decoding with the stripe edge": ("lab12.ex6", """
        _depth_from_structured_light = depth_from_structured_light
        def depth_from_structured_light(images, f, baseline):
            images = np.asarray(images)
            n, height, width = images.shape
            bits = images > 127
            k = np.zeros((height, width), int); b = np.zeros((height, width), bool)
            for g in bits:
                b = b ^ g
                k = (k << 1) | b
            z = depth_from_disparity(np.arange(width) - k * width / 2**n, f, baseline)
            return np.where(bits.any(axis=0), z, 0.0)
        """, ["left edge"]),
    "decoding that leaves undecodable pixels with a depth": ("lab12.ex6", """
        def depth_from_structured_light(images, f, baseline):
            images = np.asarray(images)
            n, height, width = images.shape
            k = np.zeros((height, width), int); b = np.zeros((height, width), bool)
            for g in images > 127:
                b = b ^ g
                k = (k << 1) | b
            column = (k + 0.5) * width / 2**n - 0.5
            return depth_from_disparity(np.arange(width) - column, f, baseline)
        """, ["undecodable pixels"]),
    # the blind set 1203b's 12/07: a running XOR along the images, packed with np.packbits (left-aligned in a byte)
    "decoding packed into a byte by np.packbits": ("lab12.ex6", """
        def depth_from_structured_light(images, f, baseline):
            stack = np.asarray(images)
            n, height, width = stack.shape
            bits = stack > 127
            binary = np.logical_xor.accumulate(bits, axis=0)
            k = np.packbits(binary, axis=0)[0].astype(np.int64)
            column = (k + 0.5) * width / 2 ** n - 0.5
            depth = depth_from_disparity(np.arange(width)[None, :] - column, f, baseline)
            depth[~bits.any(axis=0)] = 0.0
            return depth
        """, ["left-aligned in a byte", "times 2^(8 - n)"]),
    # 10 bits code a 1024-column projector: stripe indices past 255.
    "decoding into a uint8 accumulator (np.zeros_like(images[0]))": ("lab12.ex6", """
        def depth_from_structured_light(images, f, baseline):
            images = np.asarray(images)
            n, height, width = images.shape
            bits = (images > 127).astype(np.uint8)
            k = np.zeros_like(images[0]); b = np.zeros_like(images[0])
            for g in bits:
                b = b ^ g
                k = (k << 1) | b
            column = (k + 0.5) * width / 2**n - 0.5
            z = depth_from_disparity(np.arange(width)[None, :] - column, f, baseline)
            return np.where(bits.any(axis=0), z, 0.0)
        """, ["depth_from_structured_light(10 images", "with 6 images it decodes exactly",
              "the stripe indices k reach 1023"]),
    # the blind set 29d's 12/07: the stripe computed, the column Gray-coded
    "simulation showing the Gray code of the column, not of its stripe": ("lab12.ex6", """
        def simulate_structured_light(depth, f, baseline, n_bits):
            depth = np.asarray(depth, dtype=np.float64)
            height, width = depth.shape
            u = np.arange(width, dtype=np.float64)[None, :]
            lit = np.isfinite(depth) & (depth > 0)
            column = np.floor(u - f * baseline / np.where(lit, depth, 1.0) + 0.5).astype(np.int64)
            lit &= (column >= 0) & (column < width)
            stripe = (column * (1 << n_bits)) // width
            code = column ^ (column >> 1)
            images = np.zeros((n_bits, height, width), dtype=np.uint8)
            for i in range(n_bits):
                bit = (code >> (n_bits - 1 - i)) & 1
                images[i][lit] = (bit[lit] * 255).astype(np.uint8)
            return images
        """, ["each pixel shows the Gray code of its projector column itself"]),
    # the blind set 29d's 12/06: right up to 8 bits
    "patterns with the stripe index cast to uint8": ("lab12.ex6", """
        def gray_code_patterns(width, n_bits):
            k = ((np.arange(width) * (1 << n_bits)) // width).astype(np.uint8)
            g = k ^ (k >> 1)
            return (((g[None, :] >> np.arange(n_bits - 1, -1, -1)[:, None]) & 1) * 255).astype(np.uint8)
        """, ["the stripe index k is kept in 8 bits (uint8)", "the code of k mod 256"]),
    "patterns with the stripe index rounded": ("lab12.ex6", """
        def gray_code_patterns(width, n_bits):
            k = np.minimum(np.round(np.arange(width) * 2**n_bits / width).astype(int), 2**n_bits - 1)
            g = k ^ (k >> 1)
            return (((g[None, :] >> np.arange(n_bits - 1, -1, -1)[:, None]) & 1) * 255).astype(np.uint8)
        """, ["the stripe index is rounded"]),
    "simulation with the images in reverse order": ("lab12.ex6", """
        _simulate = simulate_structured_light
        def simulate_structured_light(depth, f, baseline, n_bits):
            return _simulate(depth, f, baseline, n_bits)[::-1]
        """, ["the images are in the wrong order"]),
    # ---------------------------------------------------------------- the API's conventions
    # k points of k coordinates taken for one point, or for points given as columns
    **columns_by_first_axis("triangulate", "lab12.ex1", "P1, P2, pts1, pts2", ("pts1", "pts2"), "pts1.shape[0] == 2"),
    **columns_by_first_axis("disparity_from_matches", "lab12.ex2", "xl, xr", ("xl", "xr"), "len(xl) == 2"),
    "disparity_from_matches squeezes its answer": ("lab12.ex2", """
        _reference_disparity = disparity_from_matches
        def disparity_from_matches(xl, xr):
            return np.squeeze(_reference_disparity(xl, xr))
        """, ["one-row array", "(1,)"]),
    "structured light frames of 0 and 1 (the bits not scaled to 255)": ("lab12.ex6", """
        _simulate = simulate_structured_light
        def simulate_structured_light(depth, f, baseline, n_bits):
            return (_simulate(depth, f, baseline, n_bits) > 0).astype(np.uint8)
        """, ["the lit pixels are 1, not 255"]),
    "structured light bits put together least significant first": ("lab12.ex6", """
        def depth_from_structured_light(images, f, baseline):
            images = np.asarray(images)
            n_bits, height, width = images.shape
            bits = images > 127
            binary = np.zeros((height, width), dtype=np.int64)
            bit = np.zeros((height, width), dtype=bool)
            for i in range(n_bits):
                bit = bit ^ bits[i]
                binary = binary | (bit.astype(np.int64) << i)
            column = (binary + 0.5) * width / (1 << n_bits) - 0.5
            disparity = np.arange(width)[None, :] - column
            return np.where(bits.any(axis=0), depth_from_disparity(disparity, f, baseline), 0.0)
        """, ["put together least significant first"]),
    # ---- the window's size
    # the blind set 1201c's 12/05: the weight converted with int()
    "dp_stereo with the smoothness truncated to an integer": ("lab12.ex5", """
        _dp_stereo = dp_stereo
        def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):
            weight = None if smoothness is None else int(smoothness)
            return _dp_stereo(left, right, max_disparity, block_size, weight)
        """, ["rounded down to a whole number", "converts smoothness to an integer"]),
    "block_matching sums a window of half the block size": ("lab12.ex4", """
        def _box_mean(image, block_size):
            radius = max(1, block_size // 2)
            return cv2.blur(image, (radius, radius), borderType=cv2.BORDER_REFLECT)
        """, ["keeps the square at its own disparity", "a window smaller than 9 x 9"]),
    "structured light columns kept in uint8": ("lab12.ex6", """
        def simulate_structured_light(depth, f, baseline, n_bits):
            depth = np.asarray(depth, dtype=np.float64)
            height, width = depth.shape
            patterns = gray_code_patterns(width, n_bits)
            valid = np.isfinite(depth) & (depth > 0)
            u = np.broadcast_to(np.arange(width, dtype=np.float64), depth.shape)
            disparity = np.divide(float(f) * float(baseline), depth, out=np.zeros_like(depth), where=valid)
            column = np.rint(u - disparity).astype(np.uint8).astype(np.int64)
            lit = valid & (column >= 0) & (column < width)
            images = np.zeros((int(n_bits), height, width), dtype=np.uint8)
            images[:, lit] = patterns[:, column[lit]]
            return images
        """, ["exactly as if the projector column is kept in 8 bits (uint8)"]),
    "structured light lights pixels behind the camera": ("lab12.ex6", """
        def simulate_structured_light(depth, f, baseline, n_bits):
            depth = np.asarray(depth, dtype=np.float64)
            height, width = depth.shape
            patterns = gray_code_patterns(width, n_bits)
            valid = np.isfinite(depth) & (depth != 0)
            u = np.broadcast_to(np.arange(width, dtype=np.float64), depth.shape)
            disparity = np.divide(float(f) * float(baseline), depth, out=np.zeros_like(depth), where=valid)
            column = np.floor(u - disparity + 0.5).astype(np.int64)
            lit = valid & (column >= 0) & (column < width)
            images = np.zeros((int(n_bits), height, width), dtype=np.uint8)
            images[:, lit] = patterns[:, column[lit]]
            return images
        """, ["all at Z = -3, are lit", "not in front of the camera"]),
    "structured light depth as f b / d wherever decoded": ("lab12.ex6", """
        _decoded_depth = depth_from_structured_light
        def depth_from_structured_light(images, f, baseline):
            images = np.asarray(images)
            n, h, w = images.shape
            gray = (images > 127).astype(np.int64)
            k = gray[0].copy()
            bit = gray[0].copy()
            for i in range(1, n):
                bit = bit ^ gray[i]
                k = k * 2 + bit
            centre = (k + 0.5) * w / 2 ** n - 0.5
            with np.errstate(divide="ignore"):
                z = f * baseline / (np.arange(w) - centre)
            z[~(images > 127).any(axis=0)] = 0
            return z
        """, ["decoded disparity", "is not positive"]),
    "dp_stereo with a default penalty far too weak": ("lab12.ex5", """
        _dp_right = dp_stereo
        def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):
            return _dp_right(left, right, max_disparity, block_size, 0.02 if smoothness is None else smoothness)
        """, ["the default smoothness penalty is too weak"]),
    # the blind set 1205e's 12/03: each row's backtracked path stored as collected, from the last column
    "dp_stereo storing each row's path without reversing it": ("lab12.ex5", """
        _dp_right = dp_stereo
        def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):
            return _dp_right(left, right, max_disparity, block_size, smoothness)[:, ::-1].copy()
        """, ["every row is mirrored"]),
    # the blind set 1205e's 12/04: the stripes capped at the width, where 2 ** n_bits belongs
    "gray_code_patterns with at most as many stripes as columns": ("lab12.ex6", """
        def gray_code_patterns(width, n_bits):
            stripes = min(2 ** n_bits, width)
            k = (np.arange(width) * stripes) // width
            gray = k ^ (k >> 1)
            shifts = np.arange(n_bits - 1, -1, -1)[:, None]
            return (((gray[None, :] >> shifts) & 1) * 255).astype(np.uint8)
        """, ["to `2 ** n_bits`"]),
    # the blind set 1205e's 12/02: the cost compared in the lab sheet's capitals, the default running NCC
    "block_matching comparing cost with \"SSD\" in capitals": ("lab12.ex4", """
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            if cost not in ("ssd", "ncc"):
                raise ValueError(cost)
            left, right = _grey_float(left), _grey_float(right)
            volume = (_ssd_volume if cost == "SSD" else _ncc_volume)(left, right, int(max_disparity), int(block_size))
            return np.argmin(volume, axis=0).astype(np.float64)
        """, ["cost=\"ssd\" gives exactly the map cost=\"ncc\" gives"]),
    # the blind set 1205f's 12/01: "behind the camera" read off the sign SVD gave the null vector
    "triangulate giving NaN where the SVD's null vector has a negative w": ("lab12.ex1", """
        def triangulate(P1, P2, pts1, pts2):
            single = np.ndim(pts1) == 1
            pts1, pts2 = np.reshape(pts1, (-1, 2)).astype(float), np.reshape(pts2, (-1, 2)).astype(float)
            A = np.stack([pts1[:, :1] * P1[2] - P1[0], pts1[:, 1:] * P1[2] - P1[1],
                          pts2[:, :1] * P2[2] - P2[0], pts2[:, 1:] * P2[2] - P2[1]], axis=1)
            A = A / np.linalg.norm(A, axis=2, keepdims=True)
            Xh = np.linalg.svd(A)[2][:, -1]
            X = Xh[:, :3] / Xh[:, 3:]
            X[Xh[:, 3] < 0] = np.nan
            return X[0] if single else X
        """, ["the fourth entry w of the SVD's null vector is negative"]),
    # the blind set 1205d's 12/02: the right image padded on the left, then cut back at its start (no shift)
    "block_matching shifting by np.pad then cutting the pad's columns off again": ("lab12.ex4", """
        _ncc_right = block_matching
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            if cost == "ncc":
                return _ncc_right(left, right, max_disparity, block_size, cost)
            L, R = _grey_float(left), _grey_float(right)
            height, width = L.shape
            best = np.full((height, width), np.inf)
            disparity = np.zeros((height, width))
            for d in range(min(int(max_disparity), width - 1) + 1):
                shifted = np.pad(R, ((0, 0), (d, 0)), mode="edge")[:, d:]
                ssd = _box_mean((L - shifted) ** 2, int(block_size))
                ssd[:, :d] = np.inf
                better = ssd < best
                best[better] = ssd[better]
                disparity[better] = d
            return disparity
        """, ["`np.pad(R, ((0, 0), (d, 0)), mode='edge')[:, :-d or None]`"]),
    # the blind set 1205d's 12/01: "behind the cameras" decided by the disparity's sign, not the depth
    "triangulate giving NaN where the disparity is not positive": ("lab12.ex1", """
        def triangulate(P1, P2, pts1, pts2):
            pts1 = np.asarray(pts1, dtype=np.float64)
            single = pts1.ndim == 1
            pts1, pts2 = pts1.reshape(-1, 2), np.asarray(pts2, dtype=np.float64).reshape(-1, 2)
            points = np.empty((len(pts1), 3))
            for i in range(len(pts1)):
                (xl, yl), (xr, yr) = pts1[i], pts2[i]
                A = np.array([xl * P1[2] - P1[0], yl * P1[2] - P1[1], xr * P2[2] - P2[0], yr * P2[2] - P2[1]])
                X = np.linalg.svd(A)[2][-1]
                X = X[:3] / X[3]
                if xl - xr <= 0:
                    X = np.full(3, np.nan)
                points[i] = X
            return points[0] if single else points
        """, ["is in front of both cameras", "exactly the points where the disparity x1 - x2 is <= 0"]),
    # the blind set 1205e's 12/01: "behind" read off P's third row alone, without the sign of det(P[:, :3])
    "triangulate giving NaN where P's third row is negative, whatever P's sign": ("lab12.ex1", """
        _triangulate_all = triangulate
        def triangulate(P1, P2, pts1, pts2):
            X = _triangulate_all(P1, P2, pts1, pts2)
            Xh = np.column_stack([np.reshape(X, (-1, 3)), np.ones(np.reshape(X, (-1, 3)).shape[0])])
            behind = (Xh @ np.asarray(P1)[2] <= 0) | (Xh @ np.asarray(P2)[2] <= 0)
            X = np.array(X, dtype=np.float64)
            X.reshape(-1, 3)[behind] = np.nan
            return X
        """, ["the same cameras at a negative scale", "the third coordinate of P X is <= 0"]),

    # (blind set 2026-12-06c)
    "a scanline DP whose loop over the rows stops one short": ("lab12.ex5", """
        def dp_stereo(left, right, max_disparity=64, block_size=5, smoothness=None):
            s = DEFAULT_SMOOTHNESS if smoothness is None else float(smoothness)
            left, right = _grey_float(left), _grey_float(right)
            D = int(max_disparity) + 1
            costs = _sad_volume(left, right, D - 1, int(block_size))      # (W, H, D)
            if s == 0:
                return np.argmin(costs, axis=2).T.astype(np.float64)
            width, height = costs.shape[0], costs.shape[1]
            ramp = (s * np.arange(D)).astype(np.float32)
            candidates = np.arange(D)
            disparity = np.zeros((height, width))
            for y in range(height - 1):
                row = costs[:, y, :]
                energy = np.empty_like(row)
                energy[0] = row[0]
                for x in range(1, width):
                    previous = energy[x - 1]
                    from_below = np.minimum.accumulate(previous - ramp) + ramp
                    from_above = np.minimum.accumulate((previous + ramp)[::-1])[::-1] - ramp
                    best = np.minimum(from_below, from_above)
                    energy[x] = row[x] + best - best.min()
                path = np.empty(width, dtype=np.int64)
                path[-1] = np.argmin(energy[-1])
                for x in range(width - 1, 0, -1):
                    path[x - 1] = np.argmin(energy[x - 1] + ramp[np.abs(candidates - path[x])])
                disparity[y] = path
            return disparity
        """, ["the last row is never computed"]),

    "a rig not turned taken for rectified already (identity maps where the cameras' K differ)": ("lab12.ex3",
        reference_def_with("lab12_stereo", "rectify", "height, width = np.asarray(img_l).shape[:2]",
                           "height, width = np.asarray(img_l).shape[:2]\nif np.allclose(R, np.eye(3)) and "
                           "np.allclose(T[1:], 0.0):\n    return np.asarray(img_l).copy(), np.asarray(img_r).copy(), "
                           "np.eye(3), np.eye(3)"), ["h1 and h2 are both the identity", "these two cameras' k differ"]),
}


# Conventions the API leaves open: a tip, no point lost.
ADVICE = {
    # the blind set 1205d's 12/04: T used as given, where OpenCV's calibration gives a (3, 1) column
    "rectify taking T only as a flat (3,) vector": ("lab12.ex3", """
        _rectify_flat = rectify
        def rectify(img_l, img_r, K1, K2, R, T):
            T = np.asarray(T, dtype=np.float64)
            np.cross(T, [0.0, 0.0, 1.0])   # (a (3, 1) column has no cross product with a 3-vector)
            return _rectify_flat(img_l, img_r, K1, K2, R, T)
        """, ["with T of shape (3, 1) raised", "np.ravel(T)"]),
    # the blind set 1205e's 12/05: "nothing there" tested with Z <= 0 alone, NaN going on to int(floor(nan))
    "simulate_structured_light raising on NaN depths": ("lab12.ex6", """
        _simulate_finite = simulate_structured_light
        def simulate_structured_light(depth, f, baseline, n_bits):
            depth = np.asarray(depth, dtype=np.float64)
            [int(np.floor(z)) for z in depth.ravel() if not z <= 0]   # (NaN is not <= 0)
            return _simulate_finite(depth, f, baseline, n_bits)
        """, ["rows 20-29 NaN raised", "np.isfinite"]),
    # (the left band, where x - d leaves the right image: the API leaves it open -- a tip, no point lost)
    # (the blind legitimate set 1206m's DP: the right image's first column repeated where x - d < 0)
    "DP with the x < d cost left finite (the right image's first column repeated)": ("lab12.ex5", """
        def _sad_volume(left, right, max_disparity, block_size):
            height, width = left.shape
            costs = np.zeros((max_disparity + 1, height, width), dtype=np.float32)
            for d in range(min(max_disparity, width - 1) + 1):
                costs[d] = _box_mean(np.abs(left - _shift_right(right, d)), block_size)
            return np.ascontiguousarray(costs.transpose(2, 1, 0))
        """, ["of the left strip", "larger than their column x", "no points depend on this tip"]),
    # Columns x < d have no partner in the right image: a search that compares them anyway (the right
    # image's edge repeated, zeros padded, or wrapped round) sends pixels of the left strip past it.
    "block matching with the x < d cost left finite (the right image's first column repeated)": ("lab12.ex4", """
        def _ssd_volume(left, right, max_disparity, block_size):
            height, width = left.shape
            costs = np.full((max_disparity + 1, height, width), np.inf)
            for d in range(min(max_disparity, width - 1) + 1):
                costs[d] = _box_mean((left - _shift_right(right, d)) ** 2, block_size)
            return costs
        """, ["of the left strip", "larger than their column x", "left of the right image's first column"]),
    "block matching against a zero-padded right image (np.pad), every d at every column": ("lab12.ex4", """
        def block_matching(left, right, max_disparity=64, block_size=9, cost="ssd"):
            left, right = _grey_float(left), _grey_float(right)
            width = left.shape[1]
            padded = np.pad(right, ((0, 0), (max_disparity, 0)))
            costs = [cv2.boxFilter((left - padded[:, max_disparity - d:max_disparity - d + width]) ** 2, -1,
                                   (block_size, block_size), normalize=False) for d in range(max_disparity + 1)]
            return np.argmin(np.stack(costs), axis=0).astype(np.float64)
        """, ["larger than their column x"]),
    "NCC against the right image rolled (np.roll), the wrapped columns not excluded": ("lab12.ext1", """
        def _ncc_volume(left, right, max_disparity, block_size):
            mean_l = _box_mean(left, block_size)
            std_l = np.sqrt(np.maximum(_box_mean(left * left, block_size) - mean_l ** 2, 0.0))
            costs = []
            for d in range(max_disparity + 1):
                shifted = np.roll(right, d, axis=1)
                mean_r = _box_mean(shifted, block_size)
                std_r = np.sqrt(np.maximum(_box_mean(shifted * shifted, block_size) - mean_r ** 2, 0.0))
                below = std_l * std_r
                costs.append(-np.divide(_box_mean(left * shifted, block_size) - mean_l * mean_r, below,
                                        out=np.zeros_like(below), where=below > 1e-6))
            return np.stack(costs)
        """, ["larger than their column x", "your code calls np.roll"]),
    # ---------------------------------------------------------------- ex5
    "block matching's costs without a partner marked NaN": ("lab12.ex4", """
        def _ssd_volume(left, right, max_disparity, block_size):
            height, width = left.shape
            costs = np.full((max_disparity + 1, height, width), np.nan)
            for d in range(min(max_disparity, width - 1) + 1):
                costs[d] = _box_mean((left - _shift_right(right, d)) ** 2, block_size)
                costs[d, :, :d] = np.nan
            return costs
        """, ["left of the right image's first column"]),
}
