"""MAPPO for one role's team on peg3d.vector_env (PyTorch, CPU): one actor shared by every agent of the role, which
reads its own observation (with `neighbours` slots of its nearest opponents and teammates), and one centralised
critic, which reads the game's global state and which agent it values. The other role is played on the C++ side,
by a player, a policy file or a mixture of them drawn per episode (`opponents`). With one agent in the role it is
PPO with a critic that sees the state. The result is a network `peg3d.save_policy` writes and the C++ side plays.

    from peg3d.mappo import Budget, train
    net = train(role="evader", env=dict(map="maps/open_wall.yaml", opponents={"pursuer": {"pn": 1}}), budget=Budget(steps=200_000), seed=1)
    net.save("evader.json", trained_by="peg3d.mappo")

Everything is seeded: the same arguments give the same network, bit for bit, on one torch thread.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from . import policy as _policy
from ._roles import ROLES
from .vector import VectorEnv


@dataclass(frozen=True)
class Budget:
    """How long and how a best response trains."""
    steps: int = 200_000      # env steps (games x steps), >= 1
    num_envs: int = 32        # games stepped together, in [1, 65536]
    rollout: int = 128        # steps per game per update, >= 1
    epochs: int = 4           # passes over each rollout, >= 1
    lr: float = 3e-4          # Adam's step size, > 0
    init_std: float = 0.5     # the exploration's initial standard deviation, a fraction of the steering bound, > 0
    threads: int = 1          # C++ threads stepping the games, >= 1

    def check(self, where="budget"):
        """Raises ValueError naming `where`.FIELD for a field out of its range."""
        for name, low in (("steps", 1), ("num_envs", 1), ("rollout", 1), ("epochs", 1), ("threads", 1)):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < low:
                raise ValueError(f"{where}.{name}: an integer >= {low}, not {v!r}")
        for name in ("lr", "init_std"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v <= 0:
                raise ValueError(f"{where}.{name}: a finite number > 0, not {v!r}")


class RunningStats:
    """Running mean and variance of the inputs (Chan et al.'s parallel update), saved with the network. Frozen,
    it keeps what it holds (a saved network's normalization, trained on further)."""

    def __init__(self, n):
        self.count, self.mean, self.m2 = 1e-4, np.zeros(n), np.ones(n)
        self.frozen = False

    def update(self, x):
        if self.frozen:
            return
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
    """A torch MLP, tanh between layers, orthogonal weights (gain sqrt 2; `out_scale` for the last), zero biases."""
    _torch()  # a clear error without PyTorch
    from torch import nn
    layers = []
    for i in range(len(sizes) - 1):
        lin = nn.Linear(sizes[i], sizes[i + 1])
        nn.init.orthogonal_(lin.weight, math.sqrt(2) if i < len(sizes) - 2 else out_scale)
        nn.init.zeros_(lin.bias)
        layers += [lin] + ([nn.Tanh()] if i < len(sizes) - 2 else [])
    return nn.Sequential(*layers)


def gae(r, v, v2, term, trunc, valid, gamma=0.99, lam=0.95):
    """Generalised advantage estimates over a rollout (T, ...): rewards r, values v of each step's state and v2 of
    the next, the flags; a step that is no transition (valid false: next-step autoreset's reset, an agent out of
    the game) has advantage 0 and cuts the trace. Returns (advantages, returns)."""
    adv = np.zeros(np.shape(r))
    last = np.zeros(np.shape(r)[1:])
    for t in reversed(range(len(r))):
        cont = 1.0 - (term[t] | trunc[t])
        delta = r[t] + gamma * v2[t] * (1.0 - term[t]) - v[t]
        last = np.where(valid[t], delta + gamma * lam * cont * last, 0.0)
        adv[t] = last
    return adv, adv + v


def rollout_advantages(critic, b, inputs="c", next_inputs="c2", gamma=0.99, lam=0.95):
    """gae() of a rollout's arrays b (T, N, ...: "r", "term", "trunc", "valid" and the critic's inputs b[inputs]
    of each step and b[next_inputs] of the next), valued by `critic`. Returns (advantages, returns)."""
    torch = _torch()
    with torch.no_grad():
        v = critic(torch.as_tensor(b[inputs])).squeeze(-1).numpy()
        v2 = critic(torch.as_tensor(b[next_inputs])).squeeze(-1).numpy()
    return gae(b["r"], v, v2, b["term"], b["trunc"], b["valid"], gamma, lam)


def ppo_epochs(actor, critic, log_std, opt, bound, xs, acts, logps, cs, adv, ret, epochs=4, clip=0.2,
               train_actor=True):
    """PPO's clipped updates over one rollout's transitions (flat tensors): actions are Gaussian about
    bound * tanh(actor(x)); the critic reads cs. Four minibatches per epoch; gradients clipped to norm 0.5.
    train_actor false trains the critic alone (a warm-up for a new critic under a saved actor)."""
    torch = _torch()
    params = list(actor.parameters()) + list(critic.parameters())
    adv = (adv - adv.mean()) / (adv.std() + 1e-8) if adv.numel() > 1 else adv * 0
    m = adv.shape[0]
    for _ in range(epochs):
        for chunk in torch.randperm(m).split(max(1, m // 4)):
            dist = torch.distributions.Normal(bound * torch.tanh(actor(xs[chunk])), log_std.exp())
            ratio = (dist.log_prob(acts[chunk]).sum(-1) - logps[chunk]).exp()
            pg = -torch.min(ratio * adv[chunk], ratio.clamp(1 - clip, 1 + clip) * adv[chunk]).mean()
            vl = ((critic(cs[chunk]).squeeze(-1) - ret[chunk]) ** 2).mean()
            opt.zero_grad()
            ((pg if train_actor else 0.0 * pg) + 0.5 * vl).backward()
            torch.nn.utils.clip_grad_norm_(params, 0.5)
            opt.step()


@dataclass
class Network:
    """A trained actor as save_policy takes it."""
    role: str
    observation: list
    layers: list
    action_bound: float
    input_mean: np.ndarray
    input_std: np.ndarray
    action_std: np.ndarray
    history: list  # per update: steps, games ended, the role's win rate in them

    def save(self, path, **extra):
        _policy.save_policy(path, role=self.role, observation=self.observation, layers=self.layers,
                            action_bound=self.action_bound, input_mean=self.input_mean, input_std=self.input_std,
                            action_std=self.action_std, **extra)


def _torch():
    try:
        import torch
    except ImportError as e:  # the package's own dependencies leave it out: pip install "peg3d[train]"
        raise ImportError("peg3d.mappo trains with PyTorch: pip install torch (or peg3d[train])") from e
    return torch


def train(role, env, budget=Budget(), seed=1, log=None):
    """Trains the agents of `role` (all of them, one shared actor) against the C++ players env["opponents"] gives
    the other role. `env`: vector_env's keywords but num_envs, threads and seed (map, scenario, set, opponents,
    neighbours, ...). `log(dict)` is called after every update. Returns a Network."""
    if role not in ROLES:
        raise ValueError(f"role: 'pursuer' or 'evader', not {role!r}")
    budget.check()
    torch = _torch()
    from torch import nn

    torch.manual_seed(seed)
    torch.set_num_threads(1)
    kw = dict(env)
    for key in ("num_envs", "threads", "seed"):
        if key in kw:
            raise ValueError(f"env: {key} is the budget's or the seed's, not env's")
    games = VectorEnv(num_envs=budget.num_envs, threads=budget.threads, seed=seed, **kw)
    if games.controlled[role].any():
        raise ValueError(f"env: opponents plays the {role}s; the {role}s are the ones trained")
    K = games.agent_counts[role]
    n_obs = games.single_observation_space[role].shape[-1]
    n_state = games.single_state_space.shape[0]
    bound = float(games.single_action_space[role].high[0, 0])

    actor = mlp([n_obs, 64, 64, 2], 0.01)
    critic = mlp([n_state + K, 128, 128, 1], 1.0)  # the state and a one-hot of the agent it values
    log_std = nn.Parameter(torch.full((2,), math.log(budget.init_std * bound)))
    opt = torch.optim.Adam(list(actor.parameters()) + list(critic.parameters()) + [log_std], lr=budget.lr)
    obs_stats, state_stats = RunningStats(n_obs), RunningStats(n_state)
    N, T = budget.num_envs, budget.rollout
    eye = np.broadcast_to(np.eye(K), (N, K, K))
    gamma, lam, clip = 0.99, 0.95, 0.2

    def critic_input(states):
        s = (states - state_stats.mean) / state_stats.std
        return np.concatenate([np.repeat(s[:, None, :], K, axis=1), eye], axis=-1).astype(np.float32)

    obs, _ = games.reset(seed=seed)
    x, s = obs[role].astype(np.float64), games.states().astype(np.float64)
    won = np.zeros(N, dtype=bool)  # the episode under way was won by the role (a capture; for evaders: none)
    done_steps, history = 0, []
    while done_steps < budget.steps:
        buf = {k: [] for k in ("x", "a", "logp", "r", "term", "trunc", "valid", "c", "c2")}
        ended = wins = 0
        for _ in range(T):
            obs_stats.update(x)
            state_stats.update(s)
            xn = torch.as_tensor((x - obs_stats.mean) / obs_stats.std, dtype=torch.float32)
            with torch.no_grad():
                dist = torch.distributions.Normal(bound * torch.tanh(actor(xn)), log_std.exp())
                a = dist.sample()
                logp = dist.log_prob(a).sum(-1)
            c = critic_input(s)
            obs, rew, term, trunc, info = games.step({role: a.numpy().astype(np.float64)})
            x2, s2 = obs[role].astype(np.float64), games.states().astype(np.float64)
            reset = info["reset"].astype(bool)
            buf["x"].append(xn.numpy()); buf["a"].append(a.numpy()); buf["logp"].append(logp.numpy())
            buf["r"].append(rew[role].copy()); buf["term"].append(term[role].astype(bool))
            buf["trunc"].append(trunc[role].astype(bool)); buf["valid"].append(info["acted"][role].astype(bool))
            buf["c"].append(c); buf["c2"].append(critic_input(s2))
            # A game reset now ended in the step before; the pursuers won it if it saw a capture.
            ended += int(reset.sum())
            wins += int((reset & (won if role == "pursuer" else ~won)).sum())
            won = np.where(reset, False, won | info["captured"]["evader"].any(axis=1).astype(bool))
            x, s = x2, s2
        done_steps += N * T
        b = {k: np.asarray(v) for k, v in buf.items()}  # (T, N, K, ...)
        adv, ret = rollout_advantages(critic, b, "c", "c2", gamma, lam)
        keep = b["valid"].reshape(-1)
        if not keep.any():
            continue
        flat = lambda z: torch.as_tensor(z.reshape((T * N * K,) + z.shape[3:])[keep])  # noqa: E731
        ppo_epochs(actor, critic, log_std, opt, bound, flat(b["x"]), flat(b["a"]), flat(b["logp"]), flat(b["c"]),
                   torch.as_tensor(adv.reshape(-1)[keep], dtype=torch.float32),
                   torch.as_tensor(ret.reshape(-1)[keep], dtype=torch.float32), budget.epochs, clip)
        entry = {"steps": done_steps, "games": ended, "win_rate": wins / ended if ended else None}
        history.append(entry)
        if log is not None:
            log(entry)
    layers = [(m.weight.detach().double().numpy(), m.bias.detach().double().numpy())
              for m in actor if isinstance(m, nn.Linear)]
    agent = games.observation_segments[f"{role}_0"]
    games.close()
    return Network(role=role, observation=agent, layers=layers, action_bound=bound, input_mean=obs_stats.mean,
                   input_std=obs_stats.std, action_std=log_std.detach().exp().double().numpy(), history=history)
