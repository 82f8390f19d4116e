"""Amazon Polly through boto3: SSML, lexicons, engines, speech marks, bounded parallelism.

Credentials and region come from the standard AWS chain (environment, profile, SSO,
instance role); nothing is read from the screenplay but the region. Each line takes
two requests: the audio (16 kHz `pcm`, or mp3/ogg decoded with miniaudio) and its
speech marks (`word`, `sentence`, `viseme`, and `ssml` marks for SSML lines).
Requests are spread by a limiter under the engine's rate quota and retried with
exponential backoff when Polly throttles; botocore's own retries are off so the
backoff is ours and testable.
"""

from __future__ import annotations

import json
import threading
import time
from collections.abc import Callable, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, ThreadPoolExecutor, wait
from typing import Any

from scriptc.audio import decode_compressed, wav_bytes
from scriptc.model import PollySettings, Voice
from scriptc.voices import catalog
from scriptc.voices.base import OnDone, Synthesized, SynthJob, VoiceError, VoiceInfo

API_VERSION = "2016-06-10"
# Transactions per second allowed by Polly's default quotas, per engine.
RATE_QUOTA = {"standard": 80.0, "neural": 8.0, "long-form": 8.0, "generative": 8.0}
RETRYABLE = {
    "ThrottlingException",
    "ServiceFailureException",
    "ServiceUnavailableException",
    "TooManyRequestsException",
    "RequestLimitExceeded",
}
CREDENTIAL_HINT = (
    "configure the standard AWS chain: AWS_PROFILE or AWS_ACCESS_KEY_ID/"
    "AWS_SECRET_ACCESS_KEY, ~/.aws/credentials, SSO or an instance role"
)


class RateLimiter:
    """Hands out request slots no closer than 1/rate seconds apart, across threads."""

    def __init__(
        self,
        rate: float,
        *,
        clock: Callable[[], float] = time.monotonic,
        sleep: Callable[[float], None] = time.sleep,
    ) -> None:
        self.interval = 1.0 / rate
        self.clock = clock
        self.sleep = sleep
        self.next = 0.0
        self.lock = threading.Lock()

    def acquire(self) -> None:
        with self.lock:
            now = self.clock()
            slot = max(now, self.next)
            self.next = slot + self.interval
        if slot > now:
            self.sleep(slot - now)


def _char_offset(text: str, byte_offset: int) -> int:
    return len(text.encode("utf-8")[:byte_offset].decode("utf-8", "ignore"))


def parse_marks(
    text: str, raw: bytes
) -> tuple[tuple[tuple[int, int, int], ...], tuple[tuple[str, int], ...], dict[str, Any]]:
    """Split Polly's JSON-lines speech marks into words, SSML marks and the rest."""
    words: list[tuple[int, int, int]] = []
    marks: list[tuple[str, int]] = []
    visemes: list[list[Any]] = []
    sentences: list[list[Any]] = []
    for line in raw.decode("utf-8").splitlines():
        if not line.strip():
            continue
        m = json.loads(line)
        kind, t = m.get("type"), int(m.get("time", 0))
        if kind == "word":
            words.append(
                (_char_offset(text, int(m["start"])), _char_offset(text, int(m["end"])), t)
            )
        elif kind == "ssml":
            marks.append((str(m["value"]), t))
        elif kind == "viseme":
            visemes.append([t, str(m["value"])])
        elif kind == "sentence":
            sentences.append([t, _char_offset(text, int(m["start"]))])
    return tuple(words), tuple(marks), {"visemes": visemes, "sentences": sentences}


class PollyBackend:
    name = "polly"

    def __init__(
        self,
        client: Any = None,
        *,
        sleep: Callable[[float], None] = time.sleep,
        max_attempts: int = 6,
        base_delay: float = 0.25,
        max_delay: float = 8.0,
    ) -> None:
        self._client = client
        self.sleep = sleep
        self.max_attempts = max_attempts
        self.base_delay = base_delay
        self.max_delay = max_delay
        self.region: str | None = None

    def identity(self) -> dict[str, str]:
        return {"engine": "polly", "version": API_VERSION}

    def job(
        self, cue: str, text: str, ssml: bool, voice: Voice | None, polly: PollySettings
    ) -> SynthJob:
        if voice is None:
            raise VoiceError(
                f"line {cue}: the robot has no Polly voice",
                cue=cue,
                hint="add `voice: {polly: Matthew}` to the robot",
            )
        opts = dict(voice.options)
        self.region = self.region or polly.region
        settings = (
            ("engine", str(opts.get("engine", polly.engine))),
            ("format", polly.format),
            ("lexicons", tuple(polly.lexicons)),
            ("sample_rate", polly.sample_rate),
        )
        return SynthJob(cue, text, ssml, voice.id, voice.lang, settings)

    # -- client and errors -------------------------------------------------------------

    def client(self) -> Any:
        if self._client is None:
            import boto3
            from botocore.config import Config
            from botocore.exceptions import NoRegionError

            try:
                session = boto3.session.Session(region_name=self.region)
                self._client = session.client(
                    "polly", config=Config(retries={"max_attempts": 1, "mode": "standard"})
                )
            except NoRegionError:
                raise VoiceError(
                    "no AWS region is configured for Polly",
                    hint="set AWS_REGION or `defaults: {polly: {region: eu-west-1}}`",
                ) from None
        return self._client

    def _error(self, exc: Exception, job: SynthJob | None) -> VoiceError:
        from botocore.exceptions import (
            BotoCoreError,
            ClientError,
            NoCredentialsError,
            PartialCredentialsError,
        )

        cue = job.cue if job else None
        where = f"line {cue}: " if cue else ""
        if isinstance(exc, (NoCredentialsError, PartialCredentialsError)):
            return VoiceError(
                f"{where}no AWS credentials found for Polly", cue=cue, hint=CREDENTIAL_HINT
            )
        if isinstance(exc, ClientError):
            err = exc.response.get("Error", {})
            code, msg = err.get("Code", "Unknown"), err.get("Message", "")
            voice = job.voice if job else "?"
            engine = job.setting("engine") if job else "?"
            table = {
                "UnrecognizedClientException": (
                    "the AWS credentials were rejected",
                    CREDENTIAL_HINT,
                ),
                "InvalidSignatureException": ("the AWS credentials were rejected", CREDENTIAL_HINT),
                "AccessDeniedException": (
                    "these AWS credentials may not use Polly",
                    "allow polly:SynthesizeSpeech in the IAM policy",
                ),
                "EngineNotSupportedException": (
                    f"voice {voice} does not support the {engine} engine",
                    "choose another engine or voice",
                ),
                "InvalidSsmlException": (f"Polly rejected the SSML: {msg}", "run scriptc lint"),
                "TextLengthExceededException": ("the line is too long for Polly", "split the line"),
                "LexiconNotFoundException": (
                    f"a lexicon was not found: {msg}",
                    "upload it with `aws polly put-lexicon` in this region",
                ),
                "InvalidSampleRateException": (f"bad sample rate: {msg}", None),
                "LanguageNotSupportedException": (
                    f"voice {voice} cannot speak that language: {msg}",
                    None,
                ),
            }
            if code in table:
                text, hint = table[code]
                return VoiceError(where + text, cue=cue, hint=hint)
            if code == "ValidationException" and "voice" in msg.lower():
                return VoiceError(
                    f"{where}Polly does not know voice {voice}: {msg}",
                    cue=cue,
                    hint="run `scriptc voices --engine polly`",
                )
            if code in RETRYABLE:
                return VoiceError(
                    f"{where}Polly kept throttling after {self.max_attempts} tries",
                    cue=cue,
                    hint="use fewer --jobs or ask AWS for a higher quota",
                )
            return VoiceError(f"{where}Polly request failed: {code}: {msg}", cue=cue)
        if isinstance(exc, BotoCoreError):
            return VoiceError(
                f"{where}Polly request failed: {exc}",
                cue=cue,
                hint="check the network and the AWS region",
            )
        return VoiceError(f"{where}Polly request failed: {exc!r}", cue=cue)

    def _call(self, limiter: RateLimiter, job: SynthJob, params: dict[str, Any]) -> bytes:
        from botocore.exceptions import BotoCoreError, ClientError

        attempt = 0
        while True:
            limiter.acquire()
            try:
                response = self.client().synthesize_speech(**params)
                body: bytes = response["AudioStream"].read()
                return body
            except ClientError as exc:
                code = exc.response.get("Error", {}).get("Code", "")
                attempt += 1
                if code in RETRYABLE and attempt < self.max_attempts:
                    self.sleep(min(self.max_delay, self.base_delay * 2 ** (attempt - 1)))
                    continue
                raise self._error(exc, job) from None
            except BotoCoreError as exc:
                raise self._error(exc, job) from None

    # -- synthesis --------------------------------------------------------------------

    def params(self, job: SynthJob) -> dict[str, Any]:
        p: dict[str, Any] = {
            "Engine": job.setting("engine"),
            "VoiceId": job.voice,
            "Text": job.text,
            "TextType": "ssml" if job.ssml else "text",
        }
        if job.lang:
            p["LanguageCode"] = job.lang
        if job.setting("lexicons"):
            p["LexiconNames"] = list(job.setting("lexicons"))
        return p

    def _one(self, limiter: RateLimiter, job: SynthJob) -> Synthesized:
        base = self.params(job)
        fmt, rate = job.setting("format"), int(job.setting("sample_rate"))
        audio = self._call(limiter, job, {**base, "OutputFormat": fmt, "SampleRate": str(rate)})
        types = ["word", "sentence", "viseme"] + (["ssml"] if job.ssml else [])
        raw_marks = self._call(
            limiter, job, {**base, "OutputFormat": "json", "SpeechMarkTypes": types}
        )
        if fmt == "pcm":
            wav = wav_bytes(audio, rate)
        else:
            try:
                pcm, decoded_rate = decode_compressed(audio, fmt)
            except Exception as exc:
                raise VoiceError(
                    f"line {job.cue}: cannot decode Polly's {fmt}: {exc}", cue=job.cue
                ) from None
            wav = wav_bytes(pcm, decoded_rate)
        try:
            words, marks, extra = parse_marks(job.text, raw_marks)
        except (ValueError, KeyError) as exc:
            raise VoiceError(
                f"line {job.cue}: Polly sent unreadable speech marks: {exc}", cue=job.cue
            ) from None
        return Synthesized(wav, words, marks, extra)

    def synthesize(self, jobs: Sequence[SynthJob], *, workers: int, on_done: OnDone) -> None:
        if not jobs:
            return
        known = catalog.polly_voices()
        for job in jobs:
            if known and job.voice not in known:
                raise VoiceError(
                    f"line {job.cue}: Polly does not know voice {job.voice!r}",
                    cue=job.cue,
                    hint="run `scriptc voices --engine polly`",
                )
        self.client()
        engine = str(jobs[0].setting("engine"))
        limiter = RateLimiter(RATE_QUOTA.get(engine, 8.0), sleep=self.sleep)
        with ThreadPoolExecutor(max_workers=max(1, workers)) as pool:
            futures: dict[Future[Synthesized], SynthJob] = {
                pool.submit(self._one_safe, limiter, job): job for job in jobs
            }
            pending = set(futures)
            try:
                while pending:
                    done, pending = wait(pending, return_when=FIRST_COMPLETED)
                    for fut in sorted(done, key=lambda f: futures[f].cue):
                        on_done(futures[fut], fut.result())
            except BaseException:
                for fut in pending:
                    fut.cancel()
                raise

    def _one_safe(self, limiter: RateLimiter, job: SynthJob) -> Synthesized:
        try:
            return self._one(limiter, job)
        except VoiceError:
            raise
        except Exception as exc:
            raise self._error(exc, job) from None

    def voices(self) -> list[VoiceInfo]:
        try:
            client = self.client()
            found: list[VoiceInfo] = []
            token = None
            while True:
                kwargs: dict[str, Any] = {"NextToken": token} if token else {}
                page = client.describe_voices(**kwargs)
                for v in page.get("Voices", []):
                    engines = ",".join(v.get("SupportedEngines", []))
                    found.append(
                        VoiceInfo(v["Id"], v.get("LanguageCode", ""), v.get("Gender", ""), engines)
                    )
                token = page.get("NextToken")
                if not token:
                    return sorted(found, key=lambda v: (v.language, v.id))
        except VoiceError:
            pass
        except Exception as exc:
            err = self._error(exc, None)
            if "credentials" not in str(err):
                raise err from None
        return [
            VoiceInfo(v, "", note="offline list from botocore (no AWS credentials)")
            for v in sorted(catalog.polly_voices())
        ]
