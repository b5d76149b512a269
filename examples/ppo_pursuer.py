#!/usr/bin/env python3
"""Trains a pursuer with PPO on peg3d.vector_env against C++-side evaders, with numpy and PyTorch (CPU) only,
and saves it as an MLP policy file the C++ side plays (game/mlp_policy.hpp, docs/python.md).

    .venv/bin/python examples/ppo_pursuer.py --steps 2000000 --out ppo_pursuer.json \
        --opponent flee --opponent flee-apollonius --opponent robust_0_evader.json

With several --opponent, the games are split evenly among them (one vector env per evader, stepped in turn):
every update sees every opponent.

The pursuer sees the 20 entries of its observation (no neighbours: a 1 v 1 game), normalized by running
statistics that are saved with the network. Its policy is a Gaussian about action_bound * tanh(net(obs)); the
saved file keeps the mean, which is what the C++ side plays (greedy). Autoreset is next-step: the step that
resets a game is no transition and is left out of the loss.
"""

import argparse
import json
import math
import time

import numpy as np
import torch
from torch import nn

import peg3d


class RunningStats:
    def __init__(self, n):
        self.count, self.mean, self.m2 = 1e-4, np.zeros(n), np.ones(n)

    def update(self, x):
        x = np.asarray(x, dtype=np.float64).reshape(-1, self.mean.size)
        n = x.shape[0]
        delta = x.mean(0) - self.mean
        total = self.count + n
        self.mean = self.mean + delta * n / total
        self.m2 = self.m2 + x.var(0) * n + delta**2 * self.count * n / total
        self.count = total

    @property
    def std(self):
        return np.sqrt(self.m2 / self.count + 1e-8)


def mlp(sizes, out_scale=1.0):
    layers = []
    for i in range(len(sizes) - 1):
        lin = nn.Linear(sizes[i], sizes[i + 1])
        nn.init.orthogonal_(lin.weight, math.sqrt(2) if i < len(sizes) - 2 else out_scale)
        nn.init.zeros_(lin.bias)
        layers += [lin] + ([nn.Tanh()] if i < len(sizes) - 2 else [])
    return nn.Sequential(*layers)


def save_policy(path, actor, stats, bound, opponents, trained_by="examples/ppo_pursuer.py"):
    layers = [{"weights": m.weight.detach().double().tolist(), "bias": m.bias.detach().double().tolist()}
              for m in actor if isinstance(m, nn.Linear)]
    doc = {"format": "peg3d-mlp", "version": 1, "role": "pursuer", "inputs": int(stats.mean.size),
           "action_bound": float(bound), "input_mean": stats.mean.tolist(), "input_std": stats.std.tolist(),
           "layers": layers, "trained_by": trained_by, "opponents": list(opponents)}
    with open(path, "w") as f:
        json.dump(doc, f)


class MixedOpponents:
    """One vector env per evader, the games split among them, seen as one batch of pursuer arrays."""

    def __init__(self, opponents, num_envs, seed, **kw):
        k = len(opponents)
        if num_envs < k:
            raise SystemExit(f"--num-envs {num_envs}: at least one game per opponent ({k})")
        self.sizes = [num_envs // k + (i < num_envs % k) for i in range(k)]
        self.envs = [peg3d.vector_env(num_envs=n, opponents={"evader": o}, seed=seed + i, **kw)
                     for i, (n, o) in enumerate(zip(self.sizes, opponents))]
        self.single_observation_space = self.envs[0].single_observation_space
        self.single_action_space = self.envs[0].single_action_space

    def reset(self, seed):
        return np.concatenate([e.reset(seed=seed + i)[0]["pursuer"][:, 0] for i, e in enumerate(self.envs)])

    def step(self, a):
        """The pursuer's observation, reward, terminated, truncated, acted and success flags, one row per game."""
        out, lo = [], 0
        for e, n in zip(self.envs, self.sizes):
            obs, rew, term, trunc, info = e.step({"pursuer": a[lo:lo + n, None, :]})
            out.append((obs["pursuer"][:, 0], rew["pursuer"][:, 0], term["pursuer"][:, 0], trunc["pursuer"][:, 0],
                        info["acted"]["pursuer"][:, 0], info["reward_terms"]["pursuer"]["success"][:, 0] > 0))
            lo += n
        return [np.concatenate(parts) for parts in zip(*out)]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--map", default="maps/paper.yaml")
    ap.add_argument("--opponent", action="append",
                    help="an evader: flee, flee-apollonius or a saved policy file; repeat to mix (default: flee)")
    ap.add_argument("--steps", type=int, default=1_000_000, help="env steps to train for")
    ap.add_argument("--num-envs", type=int, default=32)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--rollout", type=int, default=128, help="steps per game per update")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--set", action="append", default=[], help="configuration override key=value")
    ap.add_argument("--out", default="ppo_pursuer.json")
    args = ap.parse_args()
    opponents = args.opponent or ["flee"]
    torch.manual_seed(args.seed)
    torch.set_num_threads(1)
    settings = dict(s.split("=", 1) for s in args.set)
    env = MixedOpponents(opponents, args.num_envs, args.seed, map=args.map, threads=args.threads, neighbours=0,
                         set=settings)
    n_obs = env.single_observation_space["pursuer"].shape[-1]
    bound = float(env.single_action_space["pursuer"].high[0, 0])
    actor, critic = mlp([n_obs, 64, 64, 2], 0.01), mlp([n_obs, 64, 64, 1], 1.0)
    log_std = nn.Parameter(torch.full((2,), math.log(0.5 * bound)))
    opt = torch.optim.Adam(list(actor.parameters()) + list(critic.parameters()) + [log_std], lr=3e-4)
    stats = RunningStats(n_obs)
    gamma, lam, clip = 0.99, 0.95, 0.2
    x = env.reset(seed=args.seed).astype(np.float64)
    N, T = args.num_envs, args.rollout
    done_steps, update, start = 0, 0, time.time()
    episodes = captures = 0
    while done_steps < args.steps:
        buf = {k: [] for k in ("x", "a", "logp", "r", "term", "trunc", "valid", "x2")}
        for _ in range(T):
            stats.update(x)
            xn = torch.as_tensor((x - stats.mean) / stats.std, dtype=torch.float32)
            with torch.no_grad():
                mu = bound * torch.tanh(actor(xn))
                dist = torch.distributions.Normal(mu, log_std.exp())
                a = dist.sample()
                logp = dist.log_prob(a).sum(-1)
            o2, rew, term, trunc, acted, success = env.step(a.numpy().astype(np.float64))
            x2 = o2.astype(np.float64)
            buf["x"].append(xn.numpy()); buf["a"].append(a.numpy()); buf["logp"].append(logp.numpy())
            buf["r"].append(rew); buf["term"].append(term)
            buf["trunc"].append(trunc); buf["valid"].append(acted)
            buf["x2"].append(((x2 - stats.mean) / stats.std).astype(np.float32))
            episodes += int(((term | trunc) & acted).sum())
            captures += int((term & success).sum())
            x = x2
        done_steps += N * T
        b = {k: np.asarray(v) for k, v in buf.items()}  # (T, N, ...)
        with torch.no_grad():
            v = critic(torch.as_tensor(b["x"])).squeeze(-1).numpy()
            v2 = critic(torch.as_tensor(b["x2"])).squeeze(-1).numpy()
        adv = np.zeros((T, N))
        last = np.zeros(N)
        for t in reversed(range(T)):
            cont = 1.0 - (b["term"][t] | b["trunc"][t])
            delta = b["r"][t] + gamma * v2[t] * (1.0 - b["term"][t]) - v[t]
            last = np.where(b["valid"][t], delta + gamma * lam * cont * last, 0.0)
            adv[t] = last
        ret = adv + v
        keep = b["valid"].reshape(-1)
        data = [torch.as_tensor(z.reshape((T * N,) + z.shape[2:])[keep]) for z in (b["x"], b["a"], b["logp"])]
        adv_t = torch.as_tensor(adv.reshape(-1)[keep], dtype=torch.float32)
        ret_t = torch.as_tensor(ret.reshape(-1)[keep], dtype=torch.float32)
        adv_t = (adv_t - adv_t.mean()) / (adv_t.std() + 1e-8)
        m = adv_t.shape[0]
        for _ in range(4):
            perm = torch.randperm(m)
            for chunk in perm.split(max(1, m // 4)):
                xb, ab, lb = data[0][chunk], data[1][chunk], data[2][chunk]
                dist = torch.distributions.Normal(bound * torch.tanh(actor(xb)), log_std.exp())
                ratio = (dist.log_prob(ab).sum(-1) - lb).exp()
                pg = -torch.min(ratio * adv_t[chunk], ratio.clamp(1 - clip, 1 + clip) * adv_t[chunk]).mean()
                vl = ((critic(xb).squeeze(-1) - ret_t[chunk]) ** 2).mean()
                loss = pg + 0.5 * vl - 0.0 * dist.entropy().mean()
                opt.zero_grad()
                loss.backward()
                nn.utils.clip_grad_norm_(list(actor.parameters()) + list(critic.parameters()), 0.5)
                opt.step()
        update += 1
        if update % 10 == 0 or done_steps >= args.steps:
            rate = captures / episodes if episodes else float("nan")
            print(json.dumps({"steps": done_steps, "updates": update, "episodes": episodes, "capture_rate": rate,
                              "seconds": round(time.time() - start, 1)}), flush=True)
            episodes = captures = 0
    save_policy(args.out, actor, stats, bound, opponents)
    print(json.dumps({"saved": args.out, "seconds": round(time.time() - start, 1)}))


if __name__ == "__main__":
    main()
